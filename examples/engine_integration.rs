//! An engine embedding rgraph: it owns the device and the final target texture, loads a
//! scene once, declares its frame as a graph of the deferred plugins, and animates the
//! scene through one executor: each frame it moves the camera, the lights and one
//! object and sets the exposure through `Host::set_frame`, without reloading anything.
//! It prints, per frame, the CPU time to record and submit it, what it created (after the
//! first frame, nothing: no texture, buffer, pipeline or shader module) and the process's
//! resident memory (flat after the first frames: tests/soak.rs runs thousands).
//!
//! ```sh
//! cargo run --release --example engine_integration [-- --frames N --size W,H --out out/frame.png]
//! ```
//!
//! The Vulkan loader's environment is the engine's to set, as `rgraph` and the tests set
//! theirs: without `XDG_RUNTIME_DIR` the loader warns, and `VK_DRIVER_FILES` naming only
//! lavapipe's manifest keeps it from probing other drivers.
//!
//! Who owns what: the engine owns the device, the target (imported into the graph each
//! execution with `Imports`) and the [`Host`] (scene plus current [`FrameInputs`]); the
//! executor owns the graph's textures, pooled across frames; the deferred plugins own
//! the scene's upload and their pipelines, made on the first frame. `Host::set_frame`
//! between executions changes what the next one draws and invalidates nothing. After a
//! device loss (`ExecuteError::DeviceLost`), an engine opens a new device and runs the
//! same compiled graph through a new `Executor` on it (tests/gpu_failures.rs does).

use std::error::Error;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use rgraph_core::file::{load_str_with, GraphParams, LoadedGraph, Registry};
use rgraph_core::gpu::{
    read_rgba8, resident_bytes, AdapterChoice, DeviceObjects, Executor, Gpu, Imports,
};
use rgraph_core::types::TextureFormat;
use rgraph_core::{CompileOptions, CompiledGraph};
use rgraph_passes::{FrameInputs, Host, Overrides};
use rgraph_scene::glam::{DMat4, DQuat, DVec3};
use rgraph_scene::Scene;

/// The target's size (`--size W,H` changes it).
pub const SIZE: (u32, u32) = (640, 360);
/// The scene: five spheres on a ground plane, four point lights and a sun.
const SCENE: &str = "builtin:spheres";
/// Frames per second of the animation's clock.
const FPS: f64 = 30.0;

/// The frame: the default pipeline's branch for GPUs (pipelines/visibility_msaa_4x.ron,
/// without its scene conditions and debug views): a visibility buffer at 4x MSAA
/// rasterised in compute, its triangles rebuilt, lit and resolved in one tiled compute
/// pass, tone mapped into the engine's target (by a fragment pass: no sRGB format is a
/// storage format).
const GRAPH: &str = r#"Graph(
    resources: {
        "samples": Buffer(per_sample: 8, samples: 4),
        "resolved": Texture(format: "rgba16float"),
        "target": ImportedTexture(format: "rgba8unorm-srgb"),
    },
    passes: [
        (name: "visibility", plugin: "visibility_compute", params: (other_samples: at_edges),
         outputs: { "samples": "samples" }),
        (name: "light tiled", plugin: "light_tiled", params: (shading: adaptive),
         inputs: { "samples": "samples" }, outputs: { "resolved": "resolved" }),
        (name: "tonemap", plugin: "tonemap", params: (operator: aces),
         inputs: { "hdr": "resolved" }, outputs: { "color": "target" }),
    ],
    outputs: ["target"],
)"#;

fn main() -> Result<(), Box<dyn Error>> {
    let Options { frames, size, out } = arguments()?;
    let gpu = Gpu::open(&AdapterChoice::from_env())?;
    eprintln!("adapter: {} ({:?})", gpu.info.name, gpu.info.backend);
    let mut later = Vec::new();
    let image = animate(&gpu, frames, size, |index, frame| {
        let resident = frame.resident_bytes.map_or(String::new(), |b| {
            format!("; resident {:.1} MiB", b as f64 / 1048576.0)
        });
        eprintln!(
            "frame {index}: record+submit {:.3} ms; allocated {} textures, {} buffers; \
             created {}{resident}",
            frame.record_submit_ns as f64 / 1e6,
            frame.textures_allocated,
            frame.buffers_allocated,
            frame.created
        );
        // The frames after the first: the steady state an engine's frame loop lives in.
        if index > 0 {
            later.push(frame.record_submit_ns);
        }
    })?;
    if !later.is_empty() {
        later.sort_unstable();
        let mean = later.iter().sum::<u64>() / later.len() as u64;
        eprintln!(
            "frames 1 to {}: record+submit median {:.3} ms, mean {:.3} ms",
            frames - 1,
            later[later.len() / 2] as f64 / 1e6,
            mean as f64 / 1e6
        );
    }
    save_png(&out, size, &image)?;
    println!("{}", out.display());
    Ok(())
}

/// What one frame cost and made.
#[derive(Clone, Copy, Debug)]
pub struct FrameStats {
    /// CPU time from the executor call to its submission (`FrameReport::record_submit_ns`).
    pub record_submit_ns: u64,
    /// Graph textures and buffers the executor's pool had to create.
    pub textures_allocated: u32,
    pub buffers_allocated: u32,
    /// Device objects alive after the frame minus before it.
    pub created: DeviceObjects,
    /// The process's resident memory after the frame, where the platform tells.
    pub resident_bytes: Option<u64>,
}

/// Renders `frames` frames of the animation at `size` on `gpu` through one executor,
/// calling `each` after each frame (an engine keeps what it wants of them: a long run
/// keeps nothing), and returns the last frame's image (RGBA8, sRGB).
pub fn animate(
    gpu: &Gpu,
    frames: u32,
    size: (u32, u32),
    mut each: impl FnMut(u32, &FrameStats),
) -> Result<Vec<[u8; 4]>, Box<dyn Error>> {
    // The engine's own render target, which the graph draws into but never owns.
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("engine target"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });

    // Loaded once: the scene, and the host that owns it and its frame inputs.
    let scene = Arc::new(Scene::load(SCENE)?);
    let host = Arc::new(Host::new(scene.clone(), Overrides::default()));
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, Some(host.clone()));
    let loaded = load_str_with(
        "engine_integration.ron",
        GRAPH,
        &registry,
        &GraphParams::new(),
    )?;

    // Compiled once. A new output size or sample count would be
    // `compiled.recompile(..)`, which keeps the plans it made before.
    let options = CompileOptions {
        output_size: size,
        profile: gpu.profile(),
    };
    let mut compiled: CompiledGraph<LoadedGraph> = CompiledGraph::new(loaded, &options)?;

    let mut imports = Imports::new();
    imports.texture("target", &target);
    let mut executor = Executor::new(gpu);
    let animation = Animation::new(&scene);
    for index in 0..frames {
        host.set_frame(animation.at(f64::from(index) / FPS))?;
        let before = DeviceObjects::alive(&gpu.device);
        let report = executor.execute(&mut compiled, &imports)?;
        let frame = FrameStats {
            record_submit_ns: report.record_submit_ns,
            textures_allocated: report.textures_allocated,
            buffers_allocated: report.buffers_allocated,
            created: DeviceObjects::alive(&gpu.device).minus(&before),
            resident_bytes: resident_bytes(),
        };
        each(index, &frame);
    }
    Ok(read_rgba8(&gpu.device, &gpu.queue, &target)?)
}

/// The scene's motion: the camera orbits the scene's centre, the point lights circle it
/// the other way, the sun turns, the sphere nearest the centre bobs and the exposure
/// breathes.
struct Animation {
    start: FrameInputs,
    center: DVec3,
    /// The mesh that moves.
    bobbing: usize,
}

impl Animation {
    fn new(scene: &Scene) -> Animation {
        let center = scene.bounds.center();
        let bobbing = (0..scene.meshes.len())
            .filter_map(|i| Some((i, scene.meshes[i].world_bounds()?.center())))
            .min_by(|a, b| a.1.distance(center).total_cmp(&b.1.distance(center)))
            .map_or(0, |(i, _)| i);
        Animation {
            start: FrameInputs::of(scene),
            center,
            bobbing,
        }
    }

    /// The frame inputs at `time` seconds.
    fn at(&self, time: f64) -> FrameInputs {
        let mut inputs = self.start.clone();
        inputs.time = time;
        inputs.camera = self.start.camera.orbited(self.center, 0.4 * time);
        let turn = DQuat::from_rotation_y(-0.8 * time);
        for pose in &mut inputs.lights {
            pose.position = self.center + turn * (pose.position - self.center);
            pose.direction = turn.as_quat() * pose.direction;
        }
        let lift = DMat4::from_translation(DVec3::Y * 0.5 * (2.0 * time).sin().abs());
        inputs.transforms[self.bobbing] = lift * self.start.transforms[self.bobbing];
        inputs.exposure = 1.0 + 0.25 * (0.5 * time).sin() as f32;
        inputs
    }
}

/// What the command line asks for.
struct Options {
    frames: u32,
    size: (u32, u32),
    out: PathBuf,
}

/// `--frames N` (default 3), `--size W,H` (default [`SIZE`]) and `--out FILE` (default
/// out/frame.png).
fn arguments() -> Result<Options, String> {
    let mut options = Options {
        frames: 3,
        size: SIZE,
        out: PathBuf::from("out/frame.png"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        let positive = |text: &str| text.parse().ok().filter(|&n: &u32| n > 0);
        match flag.as_str() {
            "--frames" => {
                options.frames = positive(&value)
                    .ok_or(format!("--frames takes a positive count, not \"{value}\""))?
            }
            "--size" => {
                options.size = value
                    .split_once(',')
                    .and_then(|(w, h)| Some((positive(w)?, positive(h)?)))
                    .ok_or(format!("--size takes W,H in pixels, not \"{value}\""))?
            }
            "--out" => options.out = PathBuf::from(value),
            _ => {
                return Err(format!(
                    "unknown flag {flag} (flags: --frames N, --size W,H, --out FILE)"
                ))
            }
        }
    }
    Ok(options)
}

/// Writes the PNG through a temporary file of a random name created beside it (never
/// through a name another user could have planted a link at) and renames it, so a failed
/// write never leaves a partial image that looks finished.
fn save_png(path: &Path, size: (u32, u32), texels: &[[u8; 4]]) -> Result<(), Box<dyn Error>> {
    let dir = match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => dir,
        None => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    let image = image::RgbaImage::from_raw(size.0, size.1, texels.concat())
        .ok_or("readback size does not match the target")?;
    let mut png = std::io::Cursor::new(Vec::new());
    image.write_to(&mut png, image::ImageFormat::Png)?;
    let mut temp = tempfile::NamedTempFile::new_in(dir)?;
    temp.write_all(png.get_ref())?;
    temp.persist(path)?;
    Ok(())
}
