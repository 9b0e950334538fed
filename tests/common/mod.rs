//! Helpers shared by the GPU tests: the one way they open a device, compile against it,
//! and build the small pipelines their passes draw with.

use std::sync::Once;

use rgraph_core::gpu::{AdapterChoice, Gpu};
use rgraph_core::{CompileOptions, CompiledGraph, Graph};

/// Test textures are this size: small enough for lavapipe to run every test in a blink.
pub const SIZE: (u32, u32) = (64, 64);

/// Opens the adapter `RGRAPH_ADAPTER` names (lavapipe when unset). A machine without one
/// fails the test with the reason and the fix: GPU tests never skip silently.
pub fn gpu() -> Gpu {
    let choice = AdapterChoice::from_env();
    prepare_environment(&choice);
    Gpu::open(&choice).unwrap_or_else(|e| panic!("this test needs a Vulkan adapter: {e}"))
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
    /// The pipeline to load: the shipped file's path unless its base or a part was
    /// edited, else its copy's.
    pub path: std::path::PathBuf,
    /// The pipeline's text, edited.
    pub text: String,
    /// The copies of pipelines/ (the pipeline, its base, the parts), removed on drop.
    dir: Option<tempfile::TempDir>,
}

impl EditedPipeline {
    /// The folder of the copies, if the base or a part was edited.
    pub fn copies(&self) -> Option<&std::path::Path> {
        self.dir.as_ref().map(|dir| dir.path())
    }
}

/// The shipped pipeline `name` with each `(from, to)` of `edits` applied, every
/// occurrence, to the file that holds `from`: the pipeline itself, its preset's base or a
/// part in pipelines/parts/ (an edit of a part reaches each of its uses). With the base or
/// a part edited, the files are copies laid out as pipelines/ is, in a temporary folder;
/// with the pipeline's own text only, it keeps the shipped file's path.
pub fn edited_pipeline(name: &str, edits: &[(&str, &str)]) -> EditedPipeline {
    use std::path::Path;
    let pipelines = Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines");
    let read = |path: &Path| {
        std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
    };
    let path = pipelines.join(name);
    let mut text = read(&path);
    let base_name = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("base: \""))
        .filter(|_| text.contains("\nPreset("))
        .map(|rest| rest.trim_end_matches("\",").to_owned());
    let mut others: Vec<(String, String)> = base_name
        .iter()
        .map(|base| (base.clone(), read(&pipelines.join(base))))
        .collect();
    for part in std::fs::read_dir(pipelines.join("parts")).expect("pipelines/parts") {
        let part = part.expect("a readable folder").path();
        let name = format!("parts/{}", part.file_name().unwrap().to_string_lossy());
        others.push((name, read(&part)));
    }
    let mut copied = false;
    for (from, to) in edits {
        if text.contains(from) {
            text = text.replace(from, to);
        } else {
            let mut holding = others.iter_mut().filter(|(_, t)| t.contains(from));
            let Some((_, other)) = holding.next() else {
                panic!("{name}, its base and the parts have no \"{from}\" to edit");
            };
            *other = other.replace(from, to);
            copied = true;
            let more: Vec<&String> = holding.map(|(file, _)| &*file).collect();
            assert!(
                more.is_empty(),
                "\"{from}\" is in more files than one: {more:?}"
            );
        }
    }
    // Only the pipeline's own text edited: it loads as if it were the shipped file.
    if !copied {
        return EditedPipeline {
            path,
            text,
            dir: None,
        };
    }
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::create_dir_all(dir.path().join("parts")).expect("a temporary folder");
    for (relative, other) in &others {
        std::fs::write(dir.path().join(relative), other).expect("a writable temporary folder");
    }
    let path = dir.path().join(name);
    std::fs::write(&path, &text).expect("a writable temporary folder");
    EditedPipeline {
        path,
        text,
        dir: Some(dir),
    }
}
