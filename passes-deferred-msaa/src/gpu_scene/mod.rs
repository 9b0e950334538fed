//! The scene on the device, shared by every deferred plugin of one registry (and meant
//! for other passes that draw the same scene: forward baselines, references).
//!
//! [`SceneCache`] uploads the [`Host`]'s scene once per device, on the first
//! frame that needs it, and hands out an `Arc<GpuScene>`. A [`GpuScene`] holds:
//! - group 0 ([`GpuScene::layout`], [`GpuScene::bind_group`]), as `scene.wgsl` declares
//!   it: camera uniform, per-mesh data, materials, lights, light info, and lighting.wgsl's
//!   environment maps;
//! - the meshes ([`GpuScene::draw_meshes`], vertex layout [`mesh::VERTEX_LAYOUT`]) and a
//!   bind group per material for group 1 ([`GpuScene::material_layout`]);
//! - the light volumes ([`GpuScene::volume_lights`], [`GpuScene::volume_mesh`]).
//!
//! Everything is camera-relative: model matrices and light positions are the world ones
//! minus the camera position, computed in f64 and then cast to f32, and the camera
//! matrices only rotate and project. Call [`GpuScene::prepare`] with the output size at
//! the start of each pass's recording: it rewrites the camera for that aspect ratio when
//! it changed (one output size per frame and device is assumed).

mod camera;
mod environment;
mod layout;
mod lights;
mod materials;
pub mod mesh;
mod textures;
pub mod volumes;

use std::sync::{Arc, Mutex};

pub use camera::view_projection;
pub use lights::{camera_may_be_inside, far_plane_may_cut, VolumeLight};
pub use materials::MaterialState;
pub use mesh::MeshDraw;
pub use volumes::{VolumeMesh, VolumeShape};

use crate::analysis::{Features, GatedShader, Variant, Variants};
use crate::host::Host;
use crate::scene::{DepthConvention, Scene};

/// Which of the scene's meshes a pass draws, and in what order.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Layer {
    /// Opaque and alpha MASK meshes, in the scene's order: what the depth buffer and
    /// the G-buffer hold.
    Opaque,
    /// Alpha BLEND meshes, back to front by the distance of each mesh's bounds centre
    /// from the camera: the order over-compositing needs.
    Blended,
}

/// Uploads of one host's scene, one per device, made on first use.
pub struct SceneCache {
    host: Option<Arc<Host>>,
    features: Features,
    uploaded: Mutex<Vec<(wgpu::Device, Arc<GpuScene>)>>,
}

impl SceneCache {
    /// A cache for `host`'s scene, whose shaders compile as `variants` says; without a
    /// host, [`get`](Self::get) returns `None` and plugins draw nothing.
    pub fn new(host: Option<Arc<Host>>, variants: Variants) -> SceneCache {
        let features = host
            .as_ref()
            .map_or_else(Features::general, |h| variants.features(&h.scene));
        SceneCache {
            host,
            features,
            uploaded: Mutex::new(Vec::new()),
        }
    }

    /// The variant of `shader` that draws the scene: the code its features need (every
    /// feature's with [`Variants::General`]). A pipeline key part.
    pub fn variant(&self, shader: GatedShader) -> Variant {
        Variant::of(shader, &self.features)
    }

    /// The scene for a frame: on the frame's device (uploaded the first time) with its
    /// camera set for the output size. The camera depends only on the aspect ratio, and
    /// the shaders never read the viewport, so a target at a multiple of the output size
    /// (the reference) is fine. `None` without a host: the pass records nothing.
    pub fn for_frame(
        &self,
        resources: &graph_core::gpu::FrameResources<'_>,
    ) -> Option<Arc<GpuScene>> {
        let scene = self.get(resources.device, resources.queue)?;
        scene.prepare(resources.queue, resources.output_size());
        Some(scene)
    }

    /// The scene on `device`, uploaded through `queue` the first time.
    pub fn get(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Arc<GpuScene>> {
        let host = self.host.as_ref()?;
        let mut uploaded = self.uploaded.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, scene)) = uploaded.iter().find(|(d, _)| d == device) {
            return Some(scene.clone());
        }
        let scene = Arc::new(GpuScene::upload(device, queue, &host.scene));
        uploaded.push((device.clone(), scene.clone()));
        Some(scene)
    }
}

/// One scene's device objects; see the module documentation.
pub struct GpuScene {
    camera: crate::scene::Camera,
    layout: wgpu::BindGroupLayout,
    material_layout: wgpu::BindGroupLayout,
    cameras: camera::Cameras,
    reversed_group: wgpu::BindGroup,
    standard_group: wgpu::BindGroup,
    meshes: mesh::MeshBuffers,
    materials: materials::Materials,
    lights: lights::LightBuffers,
    sphere: VolumeMesh,
    cone: VolumeMesh,
}

impl GpuScene {
    pub fn upload(device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> GpuScene {
        let layout = layout::scene_layout(device);
        let material_layout = materials::layout(device);
        let cameras = camera::Cameras::new(device);
        let meshes = mesh::MeshBuffers::new(device, scene);
        let materials = materials::Materials::new(device, queue, scene, &material_layout);
        let (sphere, cone) = (volumes::sphere(device), volumes::cone(device));
        let lights = lights::LightBuffers::new(device, scene, &sphere, &cone);
        let environment = environment::EnvironmentMaps::new(device, queue, scene);
        let group = |camera| {
            let buffers = [
                camera,
                &meshes.data,
                &materials.data,
                &lights.data,
                &lights.info,
            ];
            layout::scene_group(device, &layout, buffers, &environment)
        };
        GpuScene {
            camera: scene.camera.clone(),
            reversed_group: group(&cameras.reversed),
            standard_group: group(&cameras.standard),
            layout,
            material_layout,
            cameras,
            meshes,
            materials,
            lights,
            sphere,
            cone,
        }
    }

    /// Writes the camera for an output of `size` if it was written for another size.
    pub fn prepare(&self, queue: &wgpu::Queue, size: (u32, u32)) {
        self.cameras.prepare(queue, &self.camera, size);
    }

    /// Group 0's layout: see scene.wgsl.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Group 0 with the camera of `convention`.
    pub fn bind_group(&self, convention: DepthConvention) -> &wgpu::BindGroup {
        match convention {
            DepthConvention::ReversedZ => &self.reversed_group,
            DepthConvention::Standard => &self.standard_group,
        }
    }

    /// The layout of each material's bind group, as material.wgsl declares it: base-color,
    /// emissive, metallicRoughness, normal and occlusion textures, each followed by its
    /// sampler (bindings 0-9).
    pub fn material_layout(&self) -> &wgpu::BindGroupLayout {
        &self.material_layout
    }

    /// Every mesh's draw and its material's pipeline state.
    pub fn mesh_draws(&self) -> impl Iterator<Item = (&MeshDraw, MaterialState)> {
        self.meshes
            .draws
            .iter()
            .filter_map(|d| Some((d, *self.materials.states.get(d.material)?)))
    }

    /// Binds the mesh buffers, then for each draw of `layer`, in its order, that `choose`
    /// accepts binds its material as `material_group` and draws it. The caller sets the
    /// pipeline in `choose`.
    pub fn draw_meshes(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        material_group: u32,
        layer: Layer,
        mut choose: impl FnMut(&mut wgpu::RenderPass<'_>, &MeshDraw, MaterialState) -> bool,
    ) {
        pass.set_vertex_buffer(0, self.meshes.vertices.slice(..));
        pass.set_index_buffer(self.meshes.indices.slice(..), wgpu::IndexFormat::Uint32);
        let mut draws: Vec<(&MeshDraw, MaterialState)> = self
            .mesh_draws()
            .filter(|(_, state)| state.blended == (layer == Layer::Blended))
            .collect();
        if layer == Layer::Blended {
            // Farthest first, sorted on every frame as a moving camera or mesh would need;
            // the sort is stable, so draws at one distance keep the scene's order.
            draws.sort_by(|(a, _), (b, _)| b.center.length().total_cmp(&a.center.length()));
        }
        for (draw, state) in draws {
            if !choose(pass, draw, state) {
                continue;
            }
            pass.set_bind_group(
                material_group,
                &self.materials.bind_groups[draw.material],
                &[],
            );
            pass.draw_indexed(
                draw.indices.clone(),
                draw.base_vertex,
                draw.instance..draw.instance + 1,
            );
        }
    }

    /// Whether a full-screen light draw has anything to add: a directional light that
    /// emits, ambient or an environment. Without one the light passes build no full-screen pipeline.
    pub fn has_fullscreen_lights(&self) -> bool {
        self.lights.fullscreen
    }

    /// Point and spot lights that reach something (so emit), each with the instance
    /// index its volume is drawn with. The light passes build volume pipelines only
    /// when there are some.
    pub fn volume_lights(&self) -> &[VolumeLight] {
        &self.lights.volumes
    }

    /// Whether the camera's near plane may cut `light`'s volume at an output of `size`.
    pub fn camera_may_be_inside(&self, light: &VolumeLight, size: (u32, u32)) -> bool {
        let aspect = f64::from(size.0.max(1)) / f64::from(size.1.max(1));
        camera_may_be_inside(&self.camera, aspect, &light.bounds)
    }

    /// Whether `light`'s volume may reach beyond the camera's finite far plane (see
    /// [`far_plane_may_cut`]).
    pub fn far_plane_may_cut(&self, light: &VolumeLight) -> bool {
        far_plane_may_cut(&self.camera, &light.bounds)
    }

    pub fn volume_mesh(&self, shape: VolumeShape) -> &VolumeMesh {
        match shape {
            VolumeShape::Sphere => &self.sphere,
            VolumeShape::Cone => &self.cone,
        }
    }
}
