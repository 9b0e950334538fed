//! Helpers shared by the GPU tests: the one way they open a device, compile against it,
//! and build the small pipelines their passes draw with.

use std::ops::Deref;
use std::sync::{Mutex, Once, PoisonError};

use rgraph_core::gpu::{AdapterChoice, Gpu};
use rgraph_core::{CompileOptions, CompiledGraph, Graph};

/// Test textures are this size: small enough for lavapipe to run every test in a blink.
pub const SIZE: (u32, u32) = (64, 64);

/// A device of the adapter `RGRAPH_ADAPTER` names (lavapipe when unset): one an earlier
/// test of this process gave back, or a new one. A machine without the adapter fails the
/// test with the reason and the fix: GPU tests never skip silently.
///
/// The deferred plugins keep the pipelines they build per device, for every graph
/// recorded on it (rgraph-passes' `kept.rs`); on lavapipe building them is most of a small
/// render's time, so tests share devices: each test has its device to itself until the
/// [`PooledGpu`] drops, and the next test to ask gets it with what it built.
pub fn gpu() -> PooledGpu {
    let given_back = POOL.lock().unwrap_or_else(PoisonError::into_inner).pop();
    let gpu = given_back.unwrap_or_else(|| {
        let choice = AdapterChoice::from_env();
        prepare_environment(&choice);
        Gpu::open(&choice).unwrap_or_else(|e| panic!("this test needs a Vulkan adapter: {e}"))
    });
    PooledGpu(Some(gpu))
}

/// Devices the tests gave back, for the next ones.
static POOL: Mutex<Vec<Gpu>> = Mutex::new(Vec::new());

/// A device from [`gpu`], the test's alone while it lives. Dropped, it goes back to the
/// pool, its unread device errors discarded (as closing it would), unless it was lost:
/// a test that destroys its device leaves it to no other.
pub struct PooledGpu(Option<Gpu>);

impl Deref for PooledGpu {
    type Target = Gpu;

    fn deref(&self) -> &Gpu {
        self.0
            .as_ref()
            .expect("a pooled device is only taken when dropped")
    }
}

impl Drop for PooledGpu {
    fn drop(&mut self) {
        let Some(gpu) = self.0.take() else { return };
        if gpu.loss.lost().is_none() {
            gpu.take_errors();
            POOL.lock()
                .unwrap_or_else(PoisonError::into_inner)
                .push(gpu);
        }
    }
}

/// Where Mesa installs lavapipe's driver manifest on x86-64 Linux.
const LAVAPIPE_ICD: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// The tests' Vulkan loader environment, as the CLI sets its own (`src/vulkan_env.rs`):
/// `XDG_RUNTIME_DIR` when unset (else the loader warns on every instance), and, for
/// lavapipe with no driver list set, only lavapipe's driver (other drivers are probed,
/// and sometimes crash, otherwise). Call it before opening any device: the first call in
/// the test process decides, before any instance reads the environment.
pub fn prepare_environment(choice: &AdapterChoice) {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
            std::env::set_var("XDG_RUNTIME_DIR", "/tmp");
        }
        let driver_list_set = std::env::var_os("VK_DRIVER_FILES").is_some()
            || std::env::var_os("VK_ICD_FILENAMES").is_some();
        if *choice == AdapterChoice::Lavapipe
            && !driver_list_set
            && std::path::Path::new(LAVAPIPE_ICD).exists()
        {
            std::env::set_var("VK_DRIVER_FILES", LAVAPIPE_ICD);
        }
    });
}

/// Compiles at [`SIZE`] against the opened device's own profile.
pub fn compile(graph: Graph, gpu: &Gpu) -> CompiledGraph {
    let options = CompileOptions {
        output_size: SIZE,
        profile: gpu.profile(),
    };
    CompiledGraph::new(graph, &options)
        .unwrap_or_else(|e| panic!("expected the graph to compile, got:\n{e}"))
}

/// A vertex stage drawing one triangle that covers the whole target (3 vertices, no
/// buffers); fragment shaders are appended to it.
pub const FULLSCREEN_VS: &str = r#"
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}
"#;

/// A render pipeline with the vertex stage `vs` and fragment stage `fs` from `wgsl`,
/// writing one target of `format` with `samples` samples, layout derived from the shader.
pub fn render_pipeline(
    device: &wgpu::Device,
    wgsl: &str,
    format: wgpu::TextureFormat,
    samples: u32,
) -> wgpu::RenderPipeline {
    render_pipeline_with(device, wgsl, Some(format), samples, None)
}

/// Like [`render_pipeline`], with an optional color target (without one, `wgsl` needs no
/// `fs`: the pipeline only writes depth) and an optional depth-stencil state.
pub fn render_pipeline_with(
    device: &wgpu::Device,
    wgsl: &str,
    format: Option<wgpu::TextureFormat>,
    samples: u32,
    depth_stencil: Option<wgpu::DepthStencilState>,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    let targets = [format.map(Into::into)];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil,
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: format.map(|_| wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A compute pipeline with the entry point `main`, layout derived from the shader.
pub fn compute_pipeline(device: &wgpu::Device, wgsl: &str) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A bind group with `layout`, binding `resources` at
/// bindings 0, 1, ...
pub fn bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: r.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &entries,
    })
}

/// A shipped pipeline with edits applied: see [`edited_pipeline`].
pub struct EditedPipeline {
    /// The pipeline to load: the shipped file's path unless it was copied, else its copy's.
    pub path: std::path::PathBuf,
    /// The pipeline's text, edited.
    pub text: String,
    /// Each file an edit landed in (the pipeline, its base or a part; the copy's path
    /// where it was copied), with its edited text, in the order of the edits.
    pub edited: Vec<(std::path::PathBuf, String)>,
    /// The copies of pipelines/ (the pipeline, its base, the parts), removed on drop.
    _dir: Option<tempfile::TempDir>,
}

/// The shipped pipeline `name` with each `(from, to)` of `edits` applied, every
/// occurrence, to the file that holds `from`: the pipeline itself, its preset's base or a
/// part in pipelines/parts/ (an edit of a part reaches each of its uses). With the base or
/// a part edited, the files are copies laid out as pipelines/ is, in a temporary folder;
/// with the pipeline's own text only, it keeps the shipped file's path.
pub fn edited_pipeline(name: &str, edits: &[(&str, &str)]) -> EditedPipeline {
    edit_pipeline(name, edits, false)
}

/// [`edited_pipeline`], always as copies: for a test that writes files beside them.
pub fn copied_pipeline(name: &str, edits: &[(&str, &str)]) -> EditedPipeline {
    edit_pipeline(name, edits, true)
}

fn edit_pipeline(name: &str, edits: &[(&str, &str)], copy: bool) -> EditedPipeline {
    use std::path::Path;
    let pipelines = Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines");
    let read = |path: &Path| {
        std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
    };
    let base_name = {
        let text = read(&pipelines.join(name));
        text.lines()
            .find_map(|l| l.trim().strip_prefix("base: \""))
            .filter(|_| text.contains("\nPreset("))
            .map(|rest| rest.trim_end_matches("\",").to_owned())
    };
    // The pipeline first, then its base and the parts, by path relative to pipelines/.
    let mut files: Vec<(String, String)> = std::iter::once(name.to_owned())
        .chain(base_name)
        .map(|file| {
            let text = read(&pipelines.join(&file));
            (file, text)
        })
        .collect();
    for part in std::fs::read_dir(pipelines.join("parts")).expect("pipelines/parts") {
        let part = part.expect("a readable folder").path();
        let file = format!("parts/{}", part.file_name().unwrap().to_string_lossy());
        files.push((file, read(&part)));
    }
    let mut landed: Vec<usize> = Vec::new();
    for (from, to) in edits {
        // The pipeline's own text first; elsewhere the edit must find one file.
        let at = match files[0].1.contains(from) {
            true => 0,
            false => {
                let holding: Vec<usize> = (1..files.len())
                    .filter(|&i| files[i].1.contains(from))
                    .collect();
                let shown: Vec<&String> = holding.iter().map(|&i| &files[i].0).collect();
                assert!(
                    !holding.is_empty(),
                    "{name}, its base and the parts have no \"{from}\" to edit"
                );
                assert!(
                    holding.len() == 1,
                    "\"{from}\" is in more files than one: {shown:?}"
                );
                holding[0]
            }
        };
        files[at].1 = files[at].1.replace(from, to);
        if !landed.contains(&at) {
            landed.push(at);
        }
    }
    // Only the pipeline's own text edited: it loads as if it were the shipped file.
    let copy = copy || landed.iter().any(|&i| i > 0);
    let dir = copy.then(|| tempfile::tempdir().expect("a temporary folder"));
    let root = dir
        .as_ref()
        .map_or(pipelines.clone(), |dir| dir.path().to_owned());
    if let Some(dir) = &dir {
        std::fs::create_dir_all(dir.path().join("parts")).expect("a temporary folder");
        for (file, text) in &files {
            std::fs::write(dir.path().join(file), text).expect("a writable temporary folder");
        }
    }
    EditedPipeline {
        path: root.join(name),
        text: files[0].1.clone(),
        edited: landed
            .iter()
            .map(|&i| (root.join(&files[i].0), files[i].1.clone()))
            .collect(),
        _dir: dir,
    }
}
