//! The scene on the device, shared by every deferred plugin of one registry (and meant
//! for other passes that draw the same scene: forward baselines, references).
//!
//! [`SceneCache`] uploads the [`Host`]'s scene once per device, on the first
//! frame that needs it, and hands out an `Arc<GpuScene>`; when the host's
//! [`FrameInputs`] change, the next frame writes the per-mesh data, lights and camera
//! they change into the same buffers (see [`crate::host`] for the contract). A
//! [`GpuScene`] holds:
//! - group 0 ([`GpuScene::layout`], [`GpuScene::bind_group`]), as `scene.wgsl` declares
//!   it: camera uniform, per-mesh data, materials, lights, light info, lighting.wgsl's
//!   environment maps, and the shadow maps' views (shadows.rs);
//! - the meshes ([`GpuScene::draw_meshes`], vertex layout [`mesh::VERTEX_LAYOUT`]) and a
//!   bind group per material for group 1 ([`GpuScene::material_layout`],
//!   [`GpuScene::material_groups`], made when a pass first draws with them);
//! - the same vertices and indices as storage buffers for visibility-buffer passes
//!   ([`GpuScene::geometry_layout`], [`GpuScene::geometry_group`], [`GpuScene::pull_meshes`]),
//!   and every material's textures as one table for their shading
//!   ([`GpuScene::texture_table_layout`], [`GpuScene::texture_table_group`]);
//! - where the deformation had the vertices in the last pose, for a G-buffer's pose
//!   offset ([`GpuScene::last_pose_group`], last_pose.rs);
//! - the light volumes ([`GpuScene::volume_lights`], [`GpuScene::volume_mesh`]);
//! - where on screen the blended meshes may be ([`GpuScene::blended_rect`]).
//!
//! Everything is camera-relative: model matrices and light positions are the world ones
//! minus the camera position, computed in f64 and then cast to f32, and the camera
//! matrices only rotate and project. Call [`GpuScene::prepare`] with the output size at
//! the start of each pass's recording: it rewrites the camera for that aspect ratio when
//! it or the frame's camera changed (one output size per frame and device is assumed).

mod camera;
mod changed;
mod deform;
mod environment;
mod geometry;
mod jitter;
pub(crate) mod last_pose;
mod layout;
mod lights;
mod materials;
pub mod mesh;
mod particles;
pub(crate) mod screen_rect;
mod seen_depths;
mod shadow_work;
mod shadows;
mod shared_geometry;
mod texture_table;
mod textures;
mod vertex_ranges;
mod view_culling;
pub(crate) mod volumes;

use std::sync::{Arc, Mutex};

use glam::DMat4;

pub use camera::view_projection;
pub use deform::PreviousPositions;
pub use jitter::{jitter, JITTER_CYCLE};
pub use lights::{camera_may_be_inside, far_plane_may_cut, VolumeLight};
pub use materials::MaterialState;
pub use mesh::MeshDraw;
pub use particles::ParticleBuffer;
pub use screen_rect::PixelRect;
pub use shadow_work::{
    MeshRuns, RasterRun, RasterRuns, ShadowOptions, ShadowStamp, ShadowWork, ViewWork,
    ITEM_TRIANGLES,
};
pub use volumes::{VolumeMesh, VolumeShape};

use crate::host::{FrameInputs, Host};
use crate::shadows::Shadows;
use crate::variant::{GatedShader, Variant, Variants};
use rgraph_scene::analysis::Features;
use rgraph_scene::{DepthConvention, Scene};

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

/// A scene on a device, or why the device cannot hold it.
type Uploaded = Result<Arc<GpuScene>, String>;

/// Uploads of one host's scene, one per device, made on first use, and brought up to the
/// host's [`FrameInputs`] when they change.
pub struct SceneCache {
    host: Option<Arc<Host>>,
    features: Features,
    /// Per device, the scene as the last frame drew it, or why the device cannot hold
    /// it (kept: the upload is not tried again).
    uploaded: Mutex<Vec<(wgpu::Device, Uploaded)>>,
    /// The bits of the f32 span each frame's camera is offset by that frame's [`jitter`]
    /// times, 0 for none: what a temporal filter among the passes asked for
    /// ([`jitter_camera`](Self::jitter_camera)).
    jitter_span: std::sync::atomic::AtomicU32,
}

impl SceneCache {
    /// A cache for `host`'s scene, whose shaders compile as `variants` says; without a
    /// host, [`get`](Self::get) returns `Ok(None)` and plugins draw nothing.
    pub fn new(host: Option<Arc<Host>>, variants: Variants) -> SceneCache {
        let features = host
            .as_ref()
            .map_or_else(Features::general, |h| variants.features(&h.scene));
        SceneCache {
            host,
            features,
            uploaded: Mutex::new(Vec::new()),
            jitter_span: std::sync::atomic::AtomicU32::new(0),
        }
    }

    /// Offsets the camera of every frame drawn from now on by the frame's [`jitter`]
    /// (numbered by the executor, `FrameResources::frame`) times `span` (1: over the
    /// whole pixel): what a temporal filter set up among this cache's passes asks for, at
    /// setup, so that every pass of a frame draws with one camera. Every pass sharing the
    /// cache is jittered, those of a plan the filter is culled from too.
    pub fn jitter_camera(&self, span: f32) {
        self.jitter_span
            .store(span.to_bits(), std::sync::atomic::Ordering::Relaxed);
    }

    /// The camera's offset in frame `frame`, in pixels: [`jitter`]'s times the span asked
    /// for, or none.
    pub fn jitter_at(&self, frame: u64) -> [f32; 2] {
        let span = f32::from_bits(self.jitter_span.load(std::sync::atomic::Ordering::Relaxed));
        jitter(frame).map(|offset| offset * span)
    }

    /// The variant of `shader` that draws the scene: the code its features need (every
    /// feature's with [`Variants::General`]). A pipeline key part.
    pub fn variant(&self, shader: GatedShader) -> Variant {
        Variant::of(shader, &self.features)
    }

    /// The host's scene, as loaded (what [`GpuScene::texture_table_group`] is made from).
    pub fn scene(&self) -> Option<&Scene> {
        self.host.as_ref().map(|h| &*h.scene)
    }

    /// `scene`'s texture table (this cache's upload of the host's scene), made the first
    /// time, for the passes that read it; or why the device cannot hold it.
    pub fn texture_table<'s>(
        &self,
        scene: &'s GpuScene,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<&'s wgpu::BindGroup, String> {
        let host = self.scene().ok_or("texture table: no scene")?;
        scene
            .texture_table_group(device, queue, host)
            .map_err(|why| format!("texture table: {why}"))
    }

    /// [`for_frame`](Self::for_frame) for a pass that reads the scene only when `reads`:
    /// `Some(None)` when it does not, `None` when it does and the frame has none (the
    /// pass then records nothing).
    pub fn for_frame_if(
        &self,
        reads: bool,
        resources: &rgraph_core::gpu::FrameResources<'_>,
    ) -> Result<Option<Option<Arc<GpuScene>>>, String> {
        match reads {
            true => Ok(self.for_frame(resources)?.map(Some)),
            false => Ok(Some(None)),
        }
    }

    /// The scene for a frame: on the frame's device (uploaded the first time), drawn as
    /// the host's current [`FrameInputs`] say, with its camera set for the output size.
    /// The camera depends only on the aspect ratio, and the shaders never read the
    /// viewport, so a target at a multiple of the output size (the reference) is fine.
    /// `None` without a host: the pass records nothing. An error when the device cannot
    /// hold the scene's geometry ([`GpuScene::upload`]).
    ///
    /// Every pass of a frame calls it; the first after [`Host::set_frame`] writes what the
    /// new inputs changed (per-mesh data, lights, camera: queue writes, which land before
    /// the frame's submission) and the others get the same scene. It creates no device
    /// object after the first upload: a scene with new inputs shares the upload's buffers
    /// and bind groups ([`GpuScene::same_upload`]).
    pub fn for_frame(
        &self,
        resources: &rgraph_core::gpu::FrameResources<'_>,
    ) -> Result<Option<Arc<GpuScene>>, String> {
        let Some(scene) = self.get(resources.device, resources.queue)? else {
            return Ok(None);
        };
        let jitter = self.jitter_at(resources.frame());
        scene.prepare(resources.queue, resources.output_size(), jitter);
        Ok(Some(scene))
    }

    /// The scene on `device` as the host's current frame inputs place it, uploaded
    /// through `queue` the first time and updated through it when the inputs changed;
    /// `None` without a host, an error when the device cannot hold its geometry.
    pub fn get(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Option<Arc<GpuScene>>, String> {
        let Some(host) = self.host.as_ref() else {
            return Ok(None);
        };
        let (inputs, generation) = host.current();
        let mut uploaded = self.uploaded.lock().unwrap_or_else(|e| e.into_inner());
        let at = match uploaded.iter().position(|(d, _)| d == device) {
            Some(at) => at,
            None => {
                let shadows = host.overrides.shadows;
                let scene = GpuScene::upload_with(
                    device,
                    queue,
                    &host.scene,
                    (inputs.clone(), generation),
                    shadows,
                );
                uploaded.push((device.clone(), scene.map(Arc::new)));
                uploaded.len() - 1
            }
        };
        let scene = uploaded[at].1.as_mut().map_err(|why| why.clone())?;
        if scene.frame.generation != generation {
            *scene = Arc::new(scene.next_frame(device, queue, &host.scene, inputs, generation));
        }
        Ok(Some(scene.clone()))
    }
}

/// One scene's device objects, and the frame they were last written for; see the module
/// documentation.
pub struct GpuScene {
    upload: Arc<Upload>,
    frame: Frame,
    /// The shadow-map work made last: this frame's, or until a pass asks, the last
    /// frame's (which this frame reuses where nothing it depends on changed).
    shadow_work: Mutex<Option<MadeWork>>,
}

/// What a frame's shadow work depends on besides the frame: output size, atlas texels,
/// options.
type ShadowKey = ((u32, u32), u32, ShadowOptions);

/// Shadow work and what it was made for.
#[derive(Clone)]
struct MadeWork {
    key: ShadowKey,
    work: Arc<ShadowWork>,
    /// Made for this frame, not carried from the last.
    this_frame: bool,
}

/// What is uploaded once per device: everything but the frame's bytes, which later
/// frames write into `meshes.data`, `lights` and `cameras`.
struct Upload {
    layout: wgpu::BindGroupLayout,
    material_layout: wgpu::BindGroupLayout,
    cameras: camera::Cameras,
    reversed_group: wgpu::BindGroup,
    standard_group: wgpu::BindGroup,
    meshes: mesh::MeshBuffers,
    /// Each deformation's reach, which bounds its mesh in a frame's pose (empty without
    /// deformations).
    reaches: Vec<Option<rgraph_scene::Reach>>,
    /// The deformation pass, for a scene with deformed meshes.
    deformer: Option<deform::Deformer>,
    /// Its replaced positions as a G-buffer's vertex stage reads them, made on first use.
    last_pose: last_pose::LastPose,
    geometry: geometry::Geometry,
    texture_table: texture_table::TextureTableGpu,
    materials: materials::Materials,
    lights: lights::LightBuffers,
    /// Which lights cast shadows (the host's choice).
    shadows: Shadows,
    shadow_maps: shadows::ShadowBuffers,
    sphere: VolumeMesh,
    cone: VolumeMesh,
    /// The object-space bounds of each of the scene's points and lines, in its order,
    /// which [`GpuScene::blended_rect`] places by the frame's transforms.
    points_lines: Vec<Option<rgraph_scene::Aabb>>,
}

/// The CPU side of one frame's inputs: what the buffers hold for it.
struct Frame {
    inputs: Arc<FrameInputs>,
    /// The host's count of `set_frame` calls these inputs came with.
    generation: u64,
    meshes: mesh::MeshFrame,
    lights: lights::LightFrame,
    deform: deform::DeformFrame,
    /// Whether the deformation ran for this frame (its pose differs from the last
    /// frame's, or this is the upload's).
    deformed: bool,
    /// How many frames since the upload's moved a shadow caster: changed a mesh's
    /// transform or the deformation's pose ([`ShadowStamp`]).
    casters_moved: u64,
}

impl Frame {
    /// `scene` placed by `inputs`, its deformed meshes bounded by `reaches`; `previous`
    /// lends what `inputs` did not change.
    fn new(
        scene: &Scene,
        (inputs, generation): (Arc<FrameInputs>, u64),
        (previous, reaches): (Option<&Frame>, &[Option<rgraph_scene::Reach>]),
        volumes: (&VolumeMesh, &VolumeMesh),
        shadows: Shadows,
    ) -> Frame {
        let eye = inputs.camera.position;
        let deform = deform::DeformFrame::new(scene, &inputs, reaches);
        let previous_meshes = previous.map(|p| (&p.meshes, p.inputs.transforms.as_slice()));
        let casters_moved = match previous {
            None => 0,
            Some(p) if p.inputs.transforms == inputs.transforms && p.deform == deform => {
                p.casters_moved
            }
            Some(p) => p.casters_moved + 1,
        };
        let lights = lights::LightFrame::new(
            scene,
            &inputs.lights,
            &inputs.camera,
            inputs.exposure,
            volumes,
            shadows,
        );
        Frame {
            meshes: mesh::MeshFrame::new(
                scene,
                (&inputs.transforms, &deform.boxes),
                eye,
                previous_meshes,
            ),
            lights,
            deform,
            deformed: false,
            casters_moved,
            inputs,
            generation,
        }
    }
}

impl GpuScene {
    /// Uploads `scene` on `device` as loaded (its own [`FrameInputs`]); an error, before
    /// its geometry is allocated, when its vertices or indices are more than the device
    /// holds in one buffer (`max_buffer_size`).
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
    ) -> Result<GpuScene, String> {
        let inputs = Arc::new(FrameInputs::of(scene));
        GpuScene::upload_with(device, queue, scene, (inputs, 0), Shadows::default())
    }

    /// Uploads `scene` on `device`, placed by `inputs` (of `generation`), its lights
    /// given shadow maps as `shadows` says.
    fn upload_with(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        inputs: (Arc<FrameInputs>, u64),
        shadows: Shadows,
    ) -> Result<GpuScene, String> {
        let (sphere, cone) = (volumes::sphere(device), volumes::cone(device));
        let reaches = deform::reaches(scene);
        let mut frame = Frame::new(scene, inputs, (None, &reaches), (&sphere, &cone), shadows);
        let layout = layout::scene_layout(device);
        let material_layout = materials::layout(device);
        let cameras = camera::Cameras::new(device);
        let meshes = mesh::MeshBuffers::new(device, queue, scene, &frame.meshes)?;
        let materials = materials::Materials::new(device, scene);
        let lights = lights::LightBuffers::new(device, &frame.lights);
        let environment = environment::EnvironmentMaps::new(device, queue, scene);
        let shadow_maps = shadows::ShadowBuffers::new(device);
        let deformer =
            deform::Deformer::new(device, scene, (&meshes.vertices, &frame.meshes.layout));
        if let Some(deformer) = &deformer {
            deformer.run(device, queue, &frame.deform);
            frame.deformed = true;
        }
        let group = |camera| {
            let buffers = [
                camera,
                &meshes.data,
                &materials.data,
                &lights.data,
                &lights.info,
            ];
            layout::scene_group(device, &layout, buffers, &environment, &shadow_maps)
        };
        let upload = Upload {
            reversed_group: group(&cameras.reversed),
            standard_group: group(&cameras.standard),
            layout,
            material_layout,
            cameras,
            meshes,
            reaches,
            deformer,
            last_pose: Default::default(),
            geometry: geometry::Geometry::new(device),
            texture_table: texture_table::TextureTableGpu::new(device),
            materials,
            lights,
            shadows,
            shadow_maps,
            sphere,
            cone,
            points_lines: (scene.points_lines.iter())
                .map(rgraph_scene::PointsLines::object_bounds)
                .collect(),
        };
        Ok(GpuScene {
            upload: Arc::new(upload),
            frame,
            shadow_work: Mutex::new(None),
        })
    }

    /// This upload placed by `inputs` (of `generation`): writes through `queue` the
    /// buffers whose contents the inputs change, deforms the vertices again on `device`
    /// when the pose of a deformed mesh changed, and shares every device object.
    fn next_frame(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        inputs: Arc<FrameInputs>,
        generation: u64,
    ) -> GpuScene {
        let upload = &self.upload;
        let volumes = (&upload.sphere, &upload.cone);
        let mut frame = Frame::new(
            scene,
            (inputs, generation),
            (Some(&self.frame), &upload.reaches),
            volumes,
            upload.shadows,
        );
        if let Some(deformer) = &upload.deformer {
            if frame.deform != self.frame.deform {
                deformer.run(device, queue, &frame.deform);
                frame.deformed = true;
            }
        }
        let writes = [
            (
                &upload.meshes.data,
                frame.meshes.bytes(),
                self.frame.meshes.bytes(),
            ),
            (
                &upload.lights.data,
                frame.lights.data_bytes(),
                self.frame.lights.data_bytes(),
            ),
            (
                &upload.lights.info,
                frame.lights.info_bytes(),
                self.frame.lights.info_bytes(),
            ),
        ];
        for (buffer, new, old) in writes {
            changed::write_changed(queue, buffer, new, old);
        }
        let made = self.shadow_work.lock().unwrap_or_else(|e| e.into_inner());
        let carried = made.as_ref().map(|made| MadeWork {
            this_frame: false,
            ..made.clone()
        });
        GpuScene {
            upload: upload.clone(),
            frame,
            shadow_work: Mutex::new(carried),
        }
    }

    /// Whether `self` and `other` are one upload (one device, one host), perhaps placed
    /// by different frame inputs: what a recorder builds against the scene's layouts
    /// (modules, pipelines) serves both.
    pub fn same_upload(&self, other: &GpuScene) -> bool {
        Arc::ptr_eq(&self.upload, &other.upload)
    }

    /// Writes the camera for an output of `size`, offset by `jitter` pixels, if it was
    /// written for another size, jitter or frame's camera.
    pub fn prepare(&self, queue: &wgpu::Queue, size: (u32, u32), jitter: [f32; 2]) {
        let camera = (&self.frame.inputs.camera, self.frame.generation);
        self.upload.cameras.prepare(queue, camera, size, jitter);
    }

    /// This frame's shadow-map work for an output of `size` and a shadow atlas `atlas`
    /// texels wide (shadow_work.rs): made by the first pass of the frame to ask, which
    /// writes the views of this frame's shadowed lights (gpu_scene/shadows.rs) through
    /// `queue`, and shared with the others that ask for the same. The write lands before
    /// the frame's submission, so every pass of the frame reads the views. Where the last
    /// frame's work has this one's stamp (nothing it was made from changed), it is this
    /// frame's too, the same `Arc`: only the views are computed again, not the culling.
    pub fn shadow_work(
        &self,
        queue: &wgpu::Queue,
        size: (u32, u32),
        atlas: u32,
        options: ShadowOptions,
    ) -> Arc<ShadowWork> {
        let key = (size, atlas, options);
        let mut made = self.shadow_work.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(made) = made.as_ref().filter(|m| m.key == key && m.this_frame) {
            return made.work.clone();
        }
        let last = made.take().filter(|m| m.key == key).map(|m| m.work);
        let work = self.make_shadow_work(queue, (size, atlas, options), last);
        *made = Some(MadeWork {
            key,
            work: work.clone(),
            this_frame: true,
        });
        work
    }

    /// The shadow work this frame made for an output of `size` and an atlas `atlas`
    /// texels wide with a compute raster's small clusters (`ShadowOptions::small_texels`),
    /// if a pass made it: what the pass that draws the rest after the compute raster
    /// draws.
    pub fn compute_shadow_work(&self, size: (u32, u32), atlas: u32) -> Option<Arc<ShadowWork>> {
        let made = self.shadow_work.lock().unwrap_or_else(|e| e.into_inner());
        let made = made.as_ref().filter(|m| m.this_frame)?;
        let (made_size, made_atlas, options) = made.key;
        let fits = made_size == size && made_atlas == atlas && options.small_texels.is_some();
        fits.then(|| made.work.clone())
    }

    /// The work for `key`: `last` where it has this frame's stamp, else made anew.
    fn make_shadow_work(
        &self,
        queue: &wgpu::Queue,
        (size, atlas, options): ShadowKey,
        last: Option<Arc<ShadowWork>>,
    ) -> Arc<ShadowWork> {
        let camera = &self.frame.inputs.camera;
        let aspect = f64::from(size.0.max(1)) / f64::from(size.1.max(1));
        // Opaque and masked meshes cast; blended ones receive too (the `transparent` pass
        // reads the maps), so the cascades cover the depths of both.
        let draws = self.layer_draws(Layer::Opaque);
        let boxes: Vec<_> = self.mesh_draws().map(|(draw, _)| draw.bounds).collect();
        let shadowed = &self.frame.lights.shadowed;
        let views = shadows::views(shadowed, camera, aspect, atlas, &boxes);
        let bytes: &[u8] = bytemuck::cast_slice(&views);
        queue.write_buffer(&self.upload.shadow_maps.views, 0, bytes);
        let stamp = ShadowStamp {
            views: bytes.to_vec(),
            atlas,
            options,
            casters_moved: self.frame.casters_moved,
        };
        if let Some(last) = last.filter(|last| last.stamp == stamp) {
            return last;
        }
        let tiles = shadows::tiles(shadowed, atlas);
        let views: Vec<_> = (tiles.into_iter())
            .zip(views.iter().map(|v| v.clip_from_world()))
            .collect();
        let clusters: usize = (draws.iter())
            .map(|(draw, _)| {
                self.upload
                    .meshes
                    .cluster_boxes(draw.instance as usize)
                    .clusters()
            })
            .sum();
        let parallel = options.culled && clusters * views.len() >= shadow_work::PARALLEL_CLUSTERS;
        let views = shadow_work::per_view(&views, parallel, |&(tile, clip_from_world)| ViewWork {
            tile,
            meshes: (draws.iter())
                .filter_map(|&(draw, state)| {
                    self.mesh_runs(draw, state, (clip_from_world, tile.2), &options)
                })
                .collect(),
        });
        Arc::new(ShadowWork { views, stamp })
    }

    /// What the view of clip space `clip_from_world`, `side` texels wide, draws of the
    /// opaque mesh `draw`: the runs of its clusters that may fall inside the view, split
    /// into small and large as `options` say, or all of it, large, unculled; `None` where
    /// it draws nothing.
    fn mesh_runs(
        &self,
        draw: &MeshDraw,
        state: MaterialState,
        (clip_from_world, side): (glam::DMat4, u32),
        options: &ShadowOptions,
    ) -> Option<MeshRuns> {
        // A deformed mesh's clusters' boxes are its rest shape's: it is drawn whole.
        let culled = options.culled && self.deformed_box(draw.instance).is_none();
        let runs = match culled {
            true => {
                let boxes = self.upload.meshes.cluster_boxes(draw.instance as usize);
                let model = self.frame.meshes.model(draw.instance);
                let fine = shadow_work::fine(options, side, state.masked);
                boxes.seen(clip_from_world, model, fine)
            }
            false => view_culling::Runs {
                small: Vec::new(),
                large: std::iter::once(0..(draw.indices.end - draw.indices.start) / 3).collect(),
            },
        };
        let empty = runs.small.is_empty() && runs.large.is_empty();
        (!empty).then_some(MeshRuns {
            instance: draw.instance,
            first_index: draw.indices.start,
            base_vertex: draw.base_vertex,
            masked: state.masked,
            runs,
        })
    }

    /// Binds the scene's index buffer, for indexed draws of [`ShadowWork`]'s runs: the
    /// vertex index is then a vertex of the scene's buffer (the run's base vertex added),
    /// which the hardware shades once for the triangles around it.
    pub fn bind_indices(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_index_buffer(
            self.upload.meshes.indices.slice(..),
            wgpu::IndexFormat::Uint32,
        );
    }

    /// The frame inputs this scene is placed by (the particle passes read the camera
    /// and the emitters).
    pub fn inputs(&self) -> &FrameInputs {
        &self.frame.inputs
    }

    /// Group 0's layout: see scene.wgsl.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.upload.layout
    }

    /// Group 0 with the camera of `convention`.
    pub fn bind_group(&self, convention: DepthConvention) -> &wgpu::BindGroup {
        match convention {
            DepthConvention::ReversedZ => &self.upload.reversed_group,
            DepthConvention::Standard => &self.upload.standard_group,
        }
    }

    /// The layout of each material's bind group, as material.wgsl declares it: base-color,
    /// emissive, metallicRoughness, normal and occlusion textures, each followed by its
    /// sampler (bindings 0-9).
    pub fn material_layout(&self) -> &wgpu::BindGroupLayout {
        &self.upload.material_layout
    }

    /// Every mesh's draw and its material's pipeline state.
    pub fn mesh_draws(&self) -> impl Iterator<Item = (&MeshDraw, MaterialState)> {
        let states = &self.upload.materials.states;
        self.frame
            .meshes
            .draws
            .iter()
            .filter_map(|d| Some((d, *states.get(d.material)?)))
    }

    /// Per material, its textures as a bind group of [`material_layout`](Self::material_layout)
    /// for `scene` (this upload's), made the first time: only passes that bind textures per
    /// draw upload them.
    pub fn material_groups(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
    ) -> &[wgpu::BindGroup] {
        let upload = &self.upload;
        upload
            .materials
            .bind_groups(device, queue, scene, &upload.material_layout)
    }

    /// Binds the mesh buffers, then for each draw of `layer`, in its order, that `choose`
    /// accepts binds its material's group of `materials` ([`material_groups`](Self::material_groups))
    /// as group `material_group` and draws it. The caller sets the pipeline in `choose`.
    pub fn draw_meshes(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        (material_group, materials): (u32, &[wgpu::BindGroup]),
        layer: Layer,
        mut choose: impl FnMut(&mut wgpu::RenderPass<'_>, &MeshDraw, MaterialState) -> bool,
    ) {
        pass.set_vertex_buffer(0, self.upload.meshes.vertices.slice(..));
        pass.set_index_buffer(
            self.upload.meshes.indices.slice(..),
            wgpu::IndexFormat::Uint32,
        );
        for (draw, state) in self.layer_draws(layer) {
            if !choose(pass, draw, state) {
                continue;
            }
            pass.set_bind_group(material_group, &materials[draw.material], &[]);
            pass.draw_indexed(
                draw.indices.clone(),
                draw.base_vertex,
                draw.instance..draw.instance + 1,
            );
        }
    }

    /// For each opaque draw that `choose` accepts, nearest first (as `draw_meshes` draws
    /// them), draws its index range without index or vertex buffers: the vertex shader
    /// pulls them (geometry.wgsl), and its vertex index is the position in the scene's
    /// index buffer, from which a visibility buffer takes triangle IDs. The caller binds
    /// [`geometry_group`](Self::geometry_group) and sets the pipeline in `choose`.
    pub fn pull_meshes(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        mut choose: impl FnMut(&mut wgpu::RenderPass<'_>, &MeshDraw, MaterialState) -> bool,
    ) {
        for (draw, state) in self.layer_draws(Layer::Opaque) {
            if choose(pass, draw, state) {
                pass.draw(draw.indices.clone(), draw.instance..draw.instance + 1);
            }
        }
    }

    /// The draws of `layer` in the order they are drawn, by the distance of their centres
    /// from the camera, sorted on every frame as a moving camera or mesh would need (the
    /// sort is stable: draws at one distance keep the scene's order). The blended layer
    /// farthest first, to blend back to front. The opaque layer nearest first, so that
    /// the depth test rejects hidden samples before they reach the sample writes, which
    /// are the cost of a multisampled G-buffer or visibility buffer (on the H200, sorting
    /// took the 4x visibility pass from 12.7 to 10.4 ms on builtin:dense); what a sample
    /// shows does not depend on the order, except between coplanar triangles.
    fn layer_draws(&self, layer: Layer) -> Vec<(&MeshDraw, MaterialState)> {
        let mut draws: Vec<(&MeshDraw, MaterialState)> = self
            .mesh_draws()
            .filter(|(_, state)| state.blended == (layer == Layer::Blended))
            .collect();
        let distance = |draw: &MeshDraw| draw.center.length();
        match layer {
            Layer::Blended => draws.sort_by(|(a, _), (b, _)| distance(b).total_cmp(&distance(a))),
            Layer::Opaque => draws.sort_by(|(a, _), (b, _)| distance(a).total_cmp(&distance(b))),
        }
        draws
    }

    /// The pixels of an output of `size` that what is drawn after the opaque scene may
    /// cover: the blended meshes and the points and lines where the frame's transforms
    /// put them (the screen rectangle of their camera-relative bounds); `None` where none
    /// is in view. One rectangle for both, so that one depth made from a compute raster's
    /// keys (`keys_depth`) serves both passes.
    pub fn blended_rect(&self, size: (u32, u32)) -> Option<PixelRect> {
        let inputs = &self.frame.inputs;
        let placed = self.upload.points_lines.iter().zip(&inputs.points_lines);
        let points_lines: Vec<rgraph_scene::Aabb> = placed
            .filter_map(|(bounds, transform)| {
                // Camera-relative in f64, as the meshes' bounds are.
                let relative = DMat4::from_translation(-inputs.camera.position) * *transform;
                Some(bounds.as_ref()?.transformed(&relative))
            })
            .collect();
        let blended = self
            .mesh_draws()
            .filter(|(_, state)| state.blended)
            .map(|(draw, _)| &draw.bounds)
            .chain(&points_lines);
        screen_rect::screen_rect(&self.frame.inputs.camera, size, blended)
    }

    /// The layout of the visibility passes' group 2: the scene's vertices (in ranges,
    /// vertex_ranges.rs) and indices as read-only storage (geometry.wgsl).
    pub fn geometry_layout(&self) -> &wgpu::BindGroupLayout {
        self.upload.geometry.layout()
    }

    /// The object-space box `Scene::meshes[mesh]` lies within this frame if skins or morph
    /// targets deform it (its [`rgraph_scene::Reach`] in the frame's pose), `None` if
    /// they do not. A deformed mesh's clusters keep their rest shape's boxes and normal
    /// cones, which the deformed vertices leave: culling takes this box for each of them
    /// instead, and no normal cone.
    pub fn deformed_box(&self, mesh: u32) -> Option<rgraph_scene::Aabb> {
        self.frame
            .deform
            .boxes
            .get(mesh as usize)
            .copied()
            .flatten()
    }

    /// Where this frame's deformation found the deformed meshes' vertices: their
    /// positions in the last frame whose pose differed, `None` where nothing deforms or
    /// this frame's pose is the last one's (the vertices stayed). A pass comparing frames
    /// (motion vectors) takes them once per [`generation`](Self::generation): the next
    /// frame's inputs replace them.
    pub fn replaced_positions(&self) -> Option<&PreviousPositions> {
        let deformer = self.upload.deformer.as_ref()?;
        self.frame.deformed.then(|| deformer.previous())
    }

    /// Group 3 of a pass whose vertex stage reads where the deformation had the vertices
    /// in the last pose (last_pose.rs: the positions its last dispatch replaced, whatever
    /// frame that was, which [`replaced_positions`](Self::replaced_positions) says), made
    /// on first use; for a scene without deformations, an empty range.
    pub fn last_pose_group(&self, device: &wgpu::Device) -> &wgpu::BindGroup {
        let upload = &self.upload;
        let previous = upload.deformer.as_ref().map(deform::Deformer::previous);
        upload.last_pose.group(device, previous)
    }

    /// The host's count of frame inputs (`set_frame` calls) this frame's came with.
    pub fn generation(&self) -> u64 {
        self.frame.generation
    }

    /// The clusters of `Scene::meshes[mesh]`, ranges of its triangles from the mesh's
    /// first in the index buffer, which holds each mesh's triangles in cluster order.
    pub fn clusters(&self, mesh: usize) -> &[rgraph_scene::Cluster] {
        self.upload.meshes.clusters(mesh)
    }

    /// The sizes in bytes of the scene's vertex and index buffers: vertex arrays that
    /// meshes share are held once, indices once per mesh (see shared_geometry.rs).
    pub fn geometry_bytes(&self) -> (u64, u64) {
        let meshes = &self.upload.meshes;
        (meshes.vertices.size(), meshes.indices.size())
    }

    /// Group 2 of the visibility passes, made on first use; an error when the device cannot
    /// bind the scene's buffers as storage.
    pub fn geometry_group(&self, device: &wgpu::Device) -> Result<&wgpu::BindGroup, &str> {
        self.upload.geometry.group(device, &self.upload.meshes)
    }

    /// The layout of the visibility shading's group 3: the scene's texture table
    /// (material_table.wgsl).
    pub fn texture_table_layout(&self) -> &wgpu::BindGroupLayout {
        self.upload.texture_table.layout()
    }

    /// Group 3 of the visibility shading for `scene` (this upload's scene), made on first
    /// use; an error when the device cannot hold the table
    /// ([`rgraph_scene::texture_table::TextureTable::check`]).
    pub fn texture_table_group(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
    ) -> Result<&wgpu::BindGroup, &str> {
        self.upload.texture_table.group(device, queue, scene)
    }

    /// Whether a full-screen light draw has anything to add: a directional light that
    /// emits, ambient or an environment. Without one the light passes build no full-screen pipeline.
    pub fn has_fullscreen_lights(&self) -> bool {
        self.frame.lights.fullscreen
    }

    /// Point and spot lights that reach something (so emit), each with the instance
    /// index its volume is drawn with. The light passes build volume pipelines only
    /// when there are some.
    pub fn volume_lights(&self) -> &[VolumeLight] {
        &self.frame.lights.volumes
    }

    /// Whether the camera's near plane may cut `light`'s volume at an output of `size`.
    pub fn camera_may_be_inside(&self, light: &VolumeLight, size: (u32, u32)) -> bool {
        let aspect = f64::from(size.0.max(1)) / f64::from(size.1.max(1));
        camera_may_be_inside(&self.frame.inputs.camera, aspect, &light.bounds)
    }

    /// Whether `light`'s volume may reach beyond the camera's finite far plane (see
    /// [`far_plane_may_cut`]).
    pub fn far_plane_may_cut(&self, light: &VolumeLight) -> bool {
        far_plane_may_cut(&self.frame.inputs.camera, &light.bounds)
    }

    /// The device mesh of the unit volume of `shape`, which light passes draw instanced,
    /// scaled and placed per light by the light data.
    pub fn volume_mesh(&self, shape: VolumeShape) -> &VolumeMesh {
        match shape {
            VolumeShape::Sphere => &self.upload.sphere,
            VolumeShape::Cone => &self.upload.cone,
        }
    }
}
