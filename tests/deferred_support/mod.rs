//! What the deferred-shading GPU tests share: rendering a pipeline file from
//! `pipelines/` with a scene on lavapipe (or the adapter `RGRAPH_ADAPTER` names) and
//! reading its exported outputs back.
//!
//! Set `DEFERRED_PNG_DIR` to also write every RGBA8 image read back there as a PNG.

pub mod measure;
pub mod samples;
pub mod scenes;
pub mod textured;
pub mod unlit;

use std::path::Path;
use std::sync::Arc;

use rgraph_core::file::{load_str_with, GraphParams, LoadedGraph, Registry};
use rgraph_core::gpu::{
    read_buffer, read_rgba16f, read_rgba8, read_texture, ExecuteError, Executor, FrameReport, Gpu,
    Imports,
};
use rgraph_core::{CompileOptions, CompiledGraph, DeviceProfile, Features, Plan};
use rgraph_passes::variant::Variants;
use rgraph_passes::{FrameInputs, Host, Overrides};
use rgraph_scene::Scene;

pub use crate::common::gpu;

/// A file in `pipelines/` and the device it is compiled for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PipelineFile<'a> {
    pub name: &'a str,
    /// Compiled as for a GPU adapter, with the device condition `cpu_device` unset: the
    /// file's branch for GPUs, run on lavapipe. Otherwise as for the adapter the tests
    /// run on.
    pub as_gpu: bool,
}

impl<'a> PipelineFile<'a> {
    /// `name` compiled for the adapter the tests run on.
    pub const fn for_device(name: &'a str) -> PipelineFile<'a> {
        PipelineFile {
            name,
            as_gpu: false,
        }
    }

    /// `name`'s branch for GPUs (see [`Self::as_gpu`]).
    pub const fn gpu_branch(name: &'a str) -> PipelineFile<'a> {
        PipelineFile { name, as_gpu: true }
    }

    /// The profile the file is compiled for on a device of `profile`.
    fn profile(&self, mut profile: DeviceProfile) -> DeviceProfile {
        profile.cpu &= !self.as_gpu;
        profile
    }

    /// The name PNG files and messages use: the file's stem, `-gpu` for the GPU branch.
    fn label(&self) -> String {
        let stem = self.name.trim_end_matches(".ron");
        match self.as_gpu {
            true => format!("{stem}-gpu"),
            false => stem.to_owned(),
        }
    }
}

impl std::fmt::Display for PipelineFile<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.as_gpu {
            true => write!(f, "{} (as on a GPU)", self.name),
            false => f.write_str(self.name),
        }
    }
}

impl<'a> From<&'a str> for PipelineFile<'a> {
    fn from(name: &'a str) -> PipelineFile<'a> {
        PipelineFile::for_device(name)
    }
}

/// One render: which pipeline, scene, overrides and size, values for the pipeline file's
/// parameters, and text edits to the file (each `(from, to)` must match) for variants no
/// file or parameter exists for.
pub struct Render<'a> {
    pub pipeline: PipelineFile<'a>,
    pub scene: &'a str,
    pub overrides: Overrides,
    pub size: (u32, u32),
    pub params: GraphParams,
    pub edits: Vec<(&'a str, &'a str)>,
    /// Changes to the loaded scene before it is handed to the plugins.
    pub scene_edit: Option<fn(&mut Scene)>,
    /// A scene built in code, rendered instead of loading `scene` (which then only
    /// names the frame in messages and PNG file names).
    pub given_scene: Option<Scene>,
    /// The features the pipeline is compiled for (none by default).
    pub features: Features,
    /// Which shader variants the plugins compile (the scene's by default).
    pub variants: Variants,
}

/// An executed frame, whose exported textures can be read back, and the executor and
/// host that can run the next one.
pub struct Frame {
    label: String,
    /// The profile the plan was compiled for: a resize keeps it.
    profile: DeviceProfile,
    host: Arc<Host>,
    compiled: CompiledGraph<LoadedGraph>,
    executor: Executor,
}

/// An RGBA8 image as read back (raw bytes, sRGB-encoded for sRGB formats).
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[u8; 4]>,
}

impl Image {
    pub fn at(&self, x: u32, y: u32) -> [u8; 4] {
        self.pixels[(y * self.width + x) as usize]
    }

    /// How many pixels are exactly `rgba`.
    pub fn count(&self, rgba: [u8; 4]) -> usize {
        self.pixels.iter().filter(|&&p| p == rgba).count()
    }
}

impl<'a> Render<'a> {
    /// `pipeline` (a file name in `pipelines/`, or a [`PipelineFile`]) with `scene` at
    /// `size`, default overrides.
    pub fn new(
        pipeline: impl Into<PipelineFile<'a>>,
        scene: &'a str,
        size: (u32, u32),
    ) -> Render<'a> {
        Render {
            pipeline: pipeline.into(),
            scene,
            overrides: Overrides::default(),
            size,
            params: GraphParams::new(),
            edits: Vec::new(),
            scene_edit: None,
            given_scene: None,
            features: Features::new(),
            variants: Variants::Scene,
        }
    }

    /// Compiles the pipeline for `features` (scene analysis's names).
    pub fn features(mut self, features: Features) -> Render<'a> {
        self.features = features;
        self
    }

    /// Renders `scene` (built in code) instead of loading `self.scene`.
    pub fn with_scene(mut self, scene: Scene) -> Render<'a> {
        self.given_scene = Some(scene);
        self
    }

    /// Compiles the shaders as `variants` says (`General`: whatever the scene).
    pub fn variants(mut self, variants: Variants) -> Render<'a> {
        self.variants = variants;
        self
    }

    pub fn scene_edit(mut self, edit: fn(&mut Scene)) -> Render<'a> {
        self.scene_edit = Some(edit);
        self
    }

    /// Loads the pipeline with its parameter `name` at `value` (`msaa` for the sample
    /// count).
    pub fn param(mut self, name: &str, value: u32) -> Render<'a> {
        self.params = self.params.with(name, value);
        self
    }

    pub fn edit(mut self, from: &'a str, to: &'a str) -> Render<'a> {
        self.edits.push((from, to));
        self
    }

    /// Also exports the resolved HDR target, for [`Frame::hdr`]`(gpu, "resolved")`.
    pub fn export_resolved(self) -> Render<'a> {
        self.edit("outputs: [\"color\"", "outputs: [\"resolved\", \"color\"")
    }

    /// Both light passes draw every light full screen instead of as a volume.
    pub fn full_screen_lights(self) -> Render<'a> {
        self.edit(
            "(mode: sample_index)",
            "(mode: sample_index, volumes: false)",
        )
        .edit(
            "plugin: \"light_nonedge\",",
            "plugin: \"light_nonedge\", params: (volumes: false),",
        )
    }

    pub fn overrides(mut self, overrides: Overrides) -> Render<'a> {
        self.overrides = overrides;
        self
    }

    /// Loads, compiles for `gpu` and executes one frame.
    pub fn run(&self, gpu: &Gpu) -> Frame {
        self.run_with(gpu.profile(), Executor::new(gpu))
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Loads, compiles for `profile` and executes one frame on an engine's own device
    /// (`device` and `queue`, whose errors and loss the engine handles), as
    /// `Executor::from_device` runs it; what the device said if the frame failed.
    pub fn try_run_on(
        &self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        profile: DeviceProfile,
    ) -> Result<Frame, String> {
        self.run_with(profile, Executor::from_device(device, queue))
    }

    fn run_with(&self, profile: DeviceProfile, mut executor: Executor) -> Result<Frame, String> {
        let mut scene = match &self.given_scene {
            Some(scene) => scene.clone(),
            None => Scene::load(self.scene)
                .unwrap_or_else(|e| panic!("cannot load scene {}: {e}", self.scene)),
        };
        if let Some(edit) = self.scene_edit {
            edit(&mut scene);
        }
        let host = Arc::new(Host::new(Arc::new(scene), self.overrides.clone()));
        let mut registry = Registry::with_builtins();
        rgraph_passes::register_with(&mut registry, Some(host.clone()), self.variants);
        let edited = crate::common::edited_pipeline(self.pipeline.name, &self.edits);
        let loaded = load_str_with(&edited.path, &edited.text, &registry, &self.params)
            .unwrap_or_else(|e| panic!("cannot load {}:\n{e}", edited.path.display()));
        let label = self.pipeline.label();
        let options = CompileOptions {
            output_size: self.size,
            profile: self.pipeline.profile(profile),
        };
        let mut compiled = CompiledGraph::new_for(loaded, &options, &self.features)
            .unwrap_or_else(|e| panic!("cannot compile {label}:\n{e}"));
        executor
            .execute(&mut compiled, &Imports::new())
            .map_err(|e| format!("{label} failed on the device: {e}"))?;
        let edited = if self.edits.is_empty() && self.scene_edit.is_none() {
            String::new()
        } else {
            "-edited".to_string()
        };
        let params: String = self
            .params
            .iter()
            .map(|(name, value)| format!("-{name}{value}"))
            .collect();
        Ok(Frame {
            label: format!(
                "{label}{params}{edited}-{}",
                self.scene.replace([':', '?', '/', '=', '&'], "_")
            ),
            profile: options.profile,
            host,
            compiled,
            executor,
        })
    }

    /// Runs one frame and reads back each of `outputs`.
    pub fn read(&self, gpu: &Gpu, outputs: &[&str]) -> Vec<Image> {
        let frame = self.run(gpu);
        outputs.iter().map(|name| frame.image(gpu, name)).collect()
    }
}

impl Frame {
    /// Runs the next frame through the same executor with `inputs`, as an engine does;
    /// the report says what it allocated.
    pub fn next(&mut self, inputs: FrameInputs) -> FrameReport {
        self.host
            .set_frame(inputs)
            .unwrap_or_else(|e| panic!("{}: {e}", self.label));
        self.executor
            .execute(&mut self.compiled, &Imports::new())
            .unwrap_or_else(|e| panic!("{} failed on the device: {e}", self.label))
    }

    /// Runs the next frame through the same executor with the inputs as they are, and
    /// returns what it said, errors included.
    pub fn try_again(&mut self) -> Result<FrameReport, ExecuteError> {
        self.executor.execute(&mut self.compiled, &Imports::new())
    }

    /// Moves the next frames to `gpu`, with a new executor there, as an engine does after
    /// its device was lost: the compiled graph and the host stay.
    pub fn move_to(&mut self, gpu: &Gpu) {
        self.executor = Executor::new(gpu);
    }

    /// Recompiles for an output of `size` (the plan's other inputs as they were) and runs
    /// the next frame, as an engine does when its window resizes.
    pub fn resize(&mut self, size: (u32, u32)) -> FrameReport {
        let options = CompileOptions {
            output_size: size,
            profile: self.profile.clone(),
        };
        // The plan's features are those of the feature set it was compiled for that the
        // graph tests, which is all a compile reads.
        let features: Features = self.compiled.plan().features.iter().cloned().collect();
        self.compiled
            .recompile(&options, &features)
            .unwrap_or_else(|e| panic!("cannot recompile {} at {size:?}:\n{e}", self.label));
        self.executor
            .execute(&mut self.compiled, &Imports::new())
            .unwrap_or_else(|e| panic!("{} failed on the device: {e}", self.label))
    }

    /// The plans compiled so far.
    pub fn plans(&self) -> &rgraph_core::PlanCache {
        self.compiled.plans()
    }

    /// The host's current frame inputs (the scene's own until [`Frame::next`]).
    pub fn inputs(&self) -> FrameInputs {
        FrameInputs::clone(&self.host.frame())
    }

    /// The plan the frame executed.
    pub fn plan(&self) -> &Plan {
        self.compiled.plan()
    }

    fn texture(&self, name: &str) -> &wgpu::Texture {
        let handle = self
            .compiled
            .graph()
            .names
            .texture(name)
            .unwrap_or_else(|| panic!("{} has no texture named {name}", self.label));
        self.executor
            .texture(self.compiled.plan(), handle.id())
            .unwrap_or_else(|| panic!("{name} is not an exported texture of {}", self.label))
    }

    /// An exported RGBA8 texture.
    pub fn image(&self, gpu: &Gpu, name: &str) -> Image {
        self.image_from((&gpu.device, &gpu.queue), name)
    }

    /// An exported RGBA8 texture of a frame on an engine's device ([`Render::try_run_on`]).
    pub fn image_from(&self, (device, queue): (&wgpu::Device, &wgpu::Queue), name: &str) -> Image {
        let texture = self.texture(name);
        let pixels = read_rgba8(device, queue, texture)
            .unwrap_or_else(|e| panic!("cannot read {name} back: {e}"));
        let image = Image {
            width: texture.width(),
            height: texture.height(),
            pixels,
        };
        if let Some(dir) = std::env::var_os("DEFERRED_PNG_DIR") {
            let file = Path::new(&dir).join(format!("{}-{name}.png", self.label));
            let bytes: Vec<u8> = image.pixels.iter().flatten().copied().collect();
            image::save_buffer(
                &file,
                &bytes,
                image.width,
                image.height,
                image::ColorType::Rgba8,
            )
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", file.display()));
        }
        image
    }

    /// The texels of mip 0 of the exported single-sampled texture `name`, as bytes, rows
    /// top first.
    pub fn texels(&self, gpu: &Gpu, name: &str) -> Vec<u8> {
        read_texture(&gpu.device, &gpu.queue, self.texture(name))
            .unwrap_or_else(|e| panic!("cannot read {name} back: {e}"))
    }

    /// The bytes of the exported buffer `name`.
    pub fn buffer(&self, gpu: &Gpu, name: &str) -> Vec<u8> {
        let handle = self
            .compiled
            .graph()
            .names
            .buffer(name)
            .unwrap_or_else(|| panic!("{} has no buffer named {name}", self.label));
        let buffer = self
            .executor
            .buffer(self.compiled.plan(), handle.id())
            .unwrap_or_else(|| panic!("{name} is not an exported buffer of {}", self.label));
        read_buffer(&gpu.device, &gpu.queue, buffer)
            .unwrap_or_else(|e| panic!("cannot read {name} back: {e}"))
    }

    /// An exported RGBA16Float texture, widened to f32.
    pub fn hdr(&self, gpu: &Gpu, name: &str) -> Vec<[f32; 4]> {
        read_rgba16f(&gpu.device, &gpu.queue, self.texture(name))
            .unwrap_or_else(|e| panic!("cannot read {name} back: {e}"))
    }
}

/// One line per pixel where two HDR images of `width` differ in any bit, naming each
/// image's value by `names`.
pub fn hdr_differences(
    a: &[[f32; 4]],
    b: &[[f32; 4]],
    width: u32,
    names: (&str, &str),
) -> Vec<String> {
    a.iter()
        .zip(b)
        .enumerate()
        .filter(|(_, (a, b))| a.map(f32::to_bits) != b.map(f32::to_bits))
        .map(|(i, (a, b))| {
            let (x, y) = (i as u32 % width, i as u32 / width);
            format!("({x}, {y}): {} {a:?}, {} {b:?}", names.0, names.1)
        })
        .collect()
}

/// The sRGB encoding of a linear value, as an 8-bit unorm.
pub fn srgb8(linear: f64) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let encoded = if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (encoded * 255.0).round() as u8
}

/// Share of `scene`'s pixels (edited by `edit`) that pipelines `a` and `b` render within
/// 1/255 at `size`, each compiled for the edited scene's features as `rgraph render`
/// compiles it.
pub fn agreement<'a>(
    (a, b): (impl Into<PipelineFile<'a>>, impl Into<PipelineFile<'a>>),
    scene: &str,
    edit: fn(&mut Scene),
    size: (u32, u32),
) -> f64 {
    let mut loaded = Scene::load(scene).unwrap_or_else(|e| panic!("cannot load {scene}: {e}"));
    edit(&mut loaded);
    let (first, second) = images((a, b), &loaded, size);
    measure::share_within(&first, &second, 1, None)
}

/// The colour images pipelines `a` and `b` render of `scene` at `size`, each compiled
/// for the scene's features as `rgraph render` compiles it.
pub fn images<'a>(
    (a, b): (impl Into<PipelineFile<'a>>, impl Into<PipelineFile<'a>>),
    scene: &Scene,
    size: (u32, u32),
) -> (Image, Image) {
    let gpu = gpu();
    let features = rgraph_scene::analysis::Features::of(scene).names();
    let image = |pipeline: PipelineFile<'a>| {
        Render::new(pipeline, &scene.name, size)
            .with_scene(scene.clone())
            .features(features.clone())
            .run(&gpu)
            .image(&gpu, "color")
    };
    (image(a.into()), image(b.into()))
}

/// A scene edit that changes nothing, for tables of scenes and edits.
pub fn unchanged(_: &mut Scene) {}
