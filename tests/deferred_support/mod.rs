//! What the deferred-shading GPU tests share: rendering a pipeline file from
//! `pipelines/` with a scene on lavapipe (or the adapter `RGRAPH_ADAPTER` names) and
//! reading its exported outputs back.
//!
//! Set `DEFERRED_PNG_DIR` to also write every image read back there as a PNG.

// Each test crate uses its own subset of these helpers.
#![allow(dead_code)]

use std::path::Path;
use std::sync::Arc;

use graph_core::file::{load_file, Registry};
use graph_core::gpu::{read_rgba8, AdapterChoice, Executor, Gpu, Imports};
use graph_core::CompileOptions;
use passes_deferred_msaa::scene::Scene;
use passes_deferred_msaa::{Host, Overrides};

/// Opens the adapter `RGRAPH_ADAPTER` names (lavapipe when unset). A machine without one
/// fails the test with the reason: GPU tests never skip silently.
pub fn gpu() -> Gpu {
    Gpu::open(&AdapterChoice::from_env())
        .unwrap_or_else(|e| panic!("this test needs a Vulkan adapter: {e}"))
}

/// An RGBA8 image as read back (raw bytes, sRGB-encoded for sRGB formats).
pub struct Image {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[u8; 4]>,
}

impl Image {
    pub fn at(&self, x: u32, y: u32) -> [u8; 4] {
        self.pixels[(y * self.width + x) as usize]
    }
}

/// One render: which pipeline, scene, overrides and size.
pub struct Render<'a> {
    pub pipeline: &'a str,
    pub scene: &'a str,
    pub overrides: Overrides,
    pub size: (u32, u32),
}

impl Render<'_> {
    /// `pipeline` (a file name in `pipelines/`) with `scene` at `size`, default overrides.
    pub fn new<'a>(pipeline: &'a str, scene: &'a str, size: (u32, u32)) -> Render<'a> {
        Render {
            pipeline,
            scene,
            overrides: Overrides::default(),
            size,
        }
    }

    /// Executes one frame and reads back each of `outputs` (names the file exports).
    pub fn read(&self, gpu: &Gpu, outputs: &[&str]) -> Vec<Image> {
        let scene = Scene::load(self.scene)
            .unwrap_or_else(|e| panic!("cannot load scene {}: {e}", self.scene));
        let mut registry = Registry::with_builtins();
        let host = Host {
            scene: Arc::new(scene),
            overrides: self.overrides.clone(),
        };
        passes_deferred_msaa::register(&mut registry, Some(Arc::new(host)));
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("pipelines")
            .join(self.pipeline);
        let mut loaded = load_file(&path, &registry)
            .unwrap_or_else(|e| panic!("cannot load {}:\n{e}", path.display()));
        let options = CompileOptions {
            output_size: self.size,
            profile: gpu.profile(),
        };
        let plan = loaded
            .compile(&options)
            .unwrap_or_else(|e| panic!("cannot compile {}:\n{e}", self.pipeline));
        let mut executor = Executor::new(gpu);
        executor
            .execute(&mut loaded.graph, &plan, &Imports::new())
            .unwrap_or_else(|e| panic!("{} failed on the device: {e}", self.pipeline));
        outputs
            .iter()
            .map(|&name| {
                let handle = loaded
                    .names
                    .texture(name)
                    .unwrap_or_else(|| panic!("{} has no texture named {name}", self.pipeline));
                let texture = executor.texture(&plan, handle.id()).unwrap_or_else(|| {
                    panic!("{name} is not an exported texture of {}", self.pipeline)
                });
                let pixels = read_rgba8(&gpu.device, &gpu.queue, texture)
                    .unwrap_or_else(|e| panic!("cannot read {name} back: {e}"));
                let image = Image {
                    name: name.to_owned(),
                    width: texture.width(),
                    height: texture.height(),
                    pixels,
                };
                save_if_asked(&image, self);
                image
            })
            .collect()
    }
}

fn save_if_asked(image: &Image, render: &Render<'_>) {
    let Some(dir) = std::env::var_os("DEFERRED_PNG_DIR") else {
        return;
    };
    let scene = render.scene.replace([':', '?', '/', '='], "_");
    let file = Path::new(&dir).join(format!(
        "{}-{scene}-{}.png",
        render.pipeline.trim_end_matches(".ron"),
        image.name
    ));
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
