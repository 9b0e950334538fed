//! `motion_vectors`: per pixel, how far the surface it shows moved on screen since the
//! previous frame, from the frame inputs (the camera and every mesh's transform) of this
//! frame and the last one this pass recorded: what a temporal filter reprojects its
//! history with (`taa`).
//!
//! ```ron
//! (name: "motion vectors", plugin: "motion_vectors",
//!  params: (view: false),            // true: the debug view instead (see below)
//!  inputs: { "ids": "ids" },          // a raster pass's visibility buffer, any samples;
//!                                     // or "samples": a compute rasteriser's keys; or
//!                                     // "depth": a G-buffer's depth, with
//!                                     // "mesh" its mesh channel where it has one, and
//!                                     // "pose_offset" its pose offset (optional)
//!  outputs: { "motion": "motion" })   // rgba16float, 1 sample; with view: "color", rgba8unorm
//! ```
//!
//! The motion is this frame's position minus the previous frame's, in pixels (x right, y
//! down), both without the jitter a temporal filter gives the camera, so a still scene
//! has none whatever the jitter; the previous position of pixel centre `c` is `c -
//! motion`. Blue holds the surface's view depth (65504, the largest half float, where
//! nothing was drawn), alpha the view depth the same point had in the previous frame: a
//! temporal filter keeping this texture's history finds there, at `c - motion`, what the
//! previous frame showed, and a nearer surface means this point was hidden then (`taa`).
//! A compute pass, an invocation per pixel:
//! - from a visibility buffer (`ids` or `samples`), the triangle of the pixel's sample 0
//!   is met by the ray through the pixel's centre, and the object-space point there is
//!   taken through its mesh's transform and the camera of each frame: a moving object's
//!   pixels move with it, the rasteriser's own files untouched. Where skins or morph
//!   targets moved the triangle's vertices since the last frame, the point is taken from
//!   where the deformation found them (the scene's replaced positions), so a waving arm
//!   moves too;
//! - from a depth buffer (`depth`, a G-buffer's), the point sample 0 holds, moved with the
//!   mesh the G-buffer's `mesh` channel says sample 0 shows (its transform's change
//!   composed with the camera's, as one matrix per mesh); without that channel the point
//!   is taken to stand still, so only the camera moves it. A depth buffer's point has no
//!   triangle to take back to the last pose of a skin or morph targets: where the
//!   G-buffer holds a pose offset ([`pose_offset`](crate::common::pose_offset), written
//!   from its triangle's vertices), the point is first moved by it, in a frame whose pose
//!   changed, so a deformed mesh's point moves with its vertices; without one, with its
//!   transform alone;
//! - where nothing was drawn, the direction of the ray, which only the camera's turn
//!   moves (an environment at infinity).
//!
//! The previous frame is the last one this pass recorded (the executor runs a pass once
//! a frame); on its first, the previous inputs are this frame's, so the motion is zero.
//! `view: true` writes the debug view `rgraph render --view motion` shows: red and green
//! 0.5 + motion / 32 pixels per axis (clamped), blue 0.5, so a still pixel is grey.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{Aspect, PassBuilder, PassKind, TextureHandle};

use crate::common::opaque_depth::OpaqueDepth;
use crate::common::optional_targets::OptionalTargets;
use crate::common::plugin::Shared;
use crate::common::pose_offset;
use crate::common::textures::{self, format_name, Input, Texels, Want};
use crate::shaders;

pub struct MotionVectors(pub(crate) Shared);

/// The motion's format: half floats (pixels to a sub-pixel precision far beyond what a
/// filter needs), x and y in red and green; four channels because WebGPU stores no
/// rg16float from a compute shader.
pub(crate) const MOTION: &[TextureFormat] = &[TextureFormat::Rgba16Float];
const VIEW: &[TextureFormat] = &[TextureFormat::Rgba8Unorm];

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MotionVectorsParams {
    /// Writes the debug view (output "color") instead of the motion (output "motion").
    pub view: bool,
    /// Fixes the depth convention of a depth buffer; left out, it follows the depth
    /// format the compile picks, as the opaque passes' does.
    pub reversed_z: Option<bool>,
}

/// What the pass reads the pixels' surfaces from.
#[derive(Copy, Clone, Debug)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) enum Surfaces {
    /// A raster pass's visibility buffer's IDs (group 1, binding 0).
    Ids(TextureHandle),
    /// A compute rasteriser's keys (whose IDs it reads), or a depth buffer.
    Depth(OpaqueDepth),
    /// A G-buffer's depth and its mesh channel (an input at group 1, binding 1), and its
    /// pose offset where the file gives it (binding 2).
    Meshes(OpaqueDepth),
}

impl Surfaces {
    /// Whether the pass rebuilds triangles from the scene's geometry (group 2), and so
    /// takes object-space points through the per-mesh matrices; the mesh channel's pass
    /// takes points relative to this frame's camera through them instead.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    fn objects(&self) -> bool {
        matches!(
            self,
            Surfaces::Ids(_) | Surfaces::Depth(OpaqueDepth::Keys(_))
        )
    }

    /// The opaque depth the pass reads, if any.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    fn depth(&self) -> Option<&OpaqueDepth> {
        match self {
            Surfaces::Depth(depth) | Surfaces::Meshes(depth) => Some(depth),
            Surfaces::Ids(_) => None,
        }
    }
}

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct MotionDispatch {
    source: String,
    view: bool,
    surfaces: Surfaces,
    /// Group 1's textures: the output at binding 7, and the IDs where read.
    inputs: Vec<Input>,
    target: TextureHandle,
}

impl Plugin for MotionVectors {
    const NAME: &'static str = "motion_vectors";
    type Params = MotionVectorsParams;

    fn kind(&self, _: &MotionVectorsParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: MotionVectorsParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let mut inputs = Vec::new();
        let mut pose = None;
        let (surfaces, samples, reader) = if slots.kind("ids").is_some() {
            let want = Want::new("the visibility buffer's triangle IDs", textures::IDS);
            let (ids, desc) = textures::input(slots, pass, "ids", want)?;
            pass.sampled(ids);
            inputs.push(Input {
                binding: 0,
                texture: ids,
                aspect: Aspect::All,
                texels: Texels::Uint,
            });
            let reader = format!(
                "{}{}",
                shaders::VISIBILITY_TEXTURES,
                shaders::MOTION_OBJECTS
            );
            (Surfaces::Ids(ids), desc.samples, reader)
        } else {
            let (depth, samples) = OpaqueDepth::read(slots, pass, params.reversed_z)?;
            let surfaces = match (depth, slots.kind("mesh").is_some()) {
                (OpaqueDepth::Buffer(..), true) => {
                    let want = Want::new("the G-buffer's mesh index", textures::MESH);
                    let (mesh, _) = textures::input(slots, pass, "mesh", want.samples(samples))?;
                    pass.sampled(mesh);
                    inputs.push(Input {
                        binding: 1,
                        texture: mesh,
                        aspect: Aspect::All,
                        texels: Texels::Uint,
                    });
                    pose = pose_offset::input(slots, pass, samples, &mut inputs)?;
                    Surfaces::Meshes(depth)
                }
                (OpaqueDepth::Keys(_), true) => {
                    return Err(PluginError::Invalid(
                        "input \"mesh\" names a G-buffer's meshes, but the keys of input \
                         \"samples\" hold their triangles already: leave it out"
                            .into(),
                    ))
                }
                (_, false) => Surfaces::Depth(depth),
            };
            let part = match surfaces {
                Surfaces::Meshes(..) => shaders::MOTION_DEPTH_MESHES,
                Surfaces::Depth(OpaqueDepth::Buffer(..)) => shaders::MOTION_DEPTH,
                _ => shaders::MOTION_OBJECTS,
            };
            (surfaces, samples, depth.wgsl() + part)
        };
        if pose.is_none() && slots.kind(pose_offset::SLOT).is_some() {
            return Err(PluginError::Invalid(
                "input \"pose_offset\" moves a G-buffer's point with its mesh's vertices: \
                 give it with the G-buffer's \"depth\" and \"mesh\""
                    .into(),
            ));
        }
        let (slot, want) = match params.view {
            true => ("color", Want::new("the motion's debug view", VIEW)),
            false => ("motion", Want::new("the motion vectors", MOTION)),
        };
        let (target, out) = textures::output(slots, pass, slot, want.samples(1), |pass, h, _| {
            pass.storage_write(h)
        })?;
        inputs.push(Input {
            binding: 7,
            texture: target,
            aspect: Aspect::All,
            texels: Texels::Store,
        });
        let format = format_name(out.format);
        // The pass for whether a frame's plan keeps the pose offset: a mesh channel's
        // reader takes its offsets from it, or none.
        let make = move |posed: bool| {
            let offsets = match surfaces {
                Surfaces::Meshes(..) => pose_offset::offset_wgsl(posed),
                Surfaces::Ids(_) | Surfaces::Depth(_) => "",
            };
            let generated = format!(
                "// Generated: the output's format, then the surfaces' reader.\n\
                 alias OutTex = texture_storage_2d<{format}, write>;\n{reader}{offsets}"
            );
            let source = shaders::MOTION
                .compose_with(samples, &generated)?
                .source()
                .to_owned();
            let kept = inputs.iter().filter(|i| pose.keeps(posed, i.texture));
            Ok(MotionDispatch {
                source,
                view: params.view,
                surfaces,
                inputs: kept.copied().collect(),
                target,
            })
        };
        self.0.record_kept(pass, pose, make)
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: the frame's matrices written into the pass's own buffer, then one
    //! dispatch of 8 x 8 pixels per workgroup.

    use std::sync::Arc;

    use glam::{DMat4, DVec4, Mat4};

    use super::{MotionDispatch, Surfaces};
    use crate::common::depth::far_depth;
    use crate::common::gpu::bindings::TextureBindings;
    use crate::common::gpu::pipeline::{module, pipeline_layout};
    use crate::common::gpu::{compute_pipeline, split_ids, Compute, Frame, InputPass, Recorded};
    use crate::common::gpu::{GroupBuffers, Recorder};
    use crate::common::opaque_depth::OpaqueDepth;
    use crate::common::textures::Input;
    use crate::gpu_scene::{view_projection, GpuScene};
    use rgraph_scene::{Camera, DepthConvention};

    /// motion.wgsl's binding of the matrices.
    const MATRICES_BINDING: u32 = 9;
    /// motion_objects.wgsl's binding of the deformed vertices' replaced positions.
    const REPLACED_BINDING: u32 = 10;

    /// Bytes of one matrix.
    const MATRIX: u64 = 64;
    /// Bytes of `Motion`'s header: two matrices, `deformed`, `depth_before` and
    /// `w_before`.
    const HEADER: u64 = 2 * MATRIX + 3 * 16;

    #[derive(Clone, PartialEq)]
    pub(crate) struct Key {
        convention: DepthConvention,
        ids: Option<wgpu::TextureFormat>,
    }

    pub(crate) struct State {
        pass: InputPass<Key, wgpu::ComputePipeline>,
        /// motion.wgsl's `Motion`, rewritten each frame.
        matrices: wgpu::Buffer,
        /// The camera and transforms of the frame recorded last.
        previous: Option<(Camera, Vec<DMat4>)>,
        /// The scene's generation (frame inputs) recorded last.
        generation: Option<u64>,
        /// Bound in place of the replaced positions where this frame has none.
        no_positions: wgpu::Buffer,
    }

    impl MotionDispatch {
        /// Group 1's textures and buffers (the matrices among them), and the
        /// convention of the depth read, if any (reversed-Z otherwise).
        fn bound(
            &self,
            resources: &rgraph_core::gpu::FrameResources<'_>,
        ) -> Result<(Vec<Input>, GroupBuffers, DepthConvention), String> {
            let bound = OpaqueDepth::bound_with(self.surfaces.depth(), &self.inputs, resources)?;
            let owned = match self.surfaces.objects() {
                true => vec![MATRICES_BINDING, REPLACED_BINDING],
                false => vec![MATRICES_BINDING],
            };
            let buffers = GroupBuffers {
                read: bound.buffers.read,
                owned,
            };
            Ok((bound.inputs, buffers, bound.convention))
        }
    }

    impl Recorder for MotionDispatch {
        type Stage = Compute;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let (inputs, buffers, _) = self.bound(resources)?;
            let inputs =
                TextureBindings::with_buffers(resources, &inputs, &buffers.read, &buffers.owned);
            let geometry = self.surfaces.objects().then(|| scene.geometry_layout());
            let layouts = [Some(scene.layout()), Some(&inputs.layout), geometry];
            let meshes = scene.inputs().transforms.len().max(1) as u64;
            Ok(State {
                pass: InputPass {
                    module: module(device, "motion vectors", &self.source),
                    layout: pipeline_layout(
                        device,
                        &layouts[..2 + usize::from(geometry.is_some())],
                    ),
                    inputs,
                    pipelines: Default::default(),
                },
                matrices: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("motion vectors' matrices"),
                    size: HEADER + 2 * MATRIX * meshes,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                previous: None,
                generation: None,
                no_positions: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("motion vectors' no replaced positions"),
                    size: 16,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                }),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let (_, _, convention) = self.bound(resources)?;
            let inputs = scene.inputs();
            let current = (inputs.camera.clone(), inputs.transforms.clone());
            let previous = state.previous.replace(current.clone());
            // The deformation's replaced positions are the last pose's once per frame
            // inputs, and only where this pass recorded a frame before.
            let generation = state.generation.replace(scene.generation());
            let replaced = scene
                .replaced_positions()
                .filter(|_| previous.is_some() && generation != Some(scene.generation()));
            let previous = previous.unwrap_or(current.clone());
            let size = resources.output_size();
            let space = match self.surfaces.objects() {
                true => MeshSpace::Object,
                false => MeshSpace::CameraRelative,
            };
            let matrices = matrices(&current, &previous, size, convention, space);
            let deformed: [u32; 4] = match replaced {
                Some(positions) => [positions.first, positions.end, 1, 0],
                None => [0; 4],
            };
            let mut bytes = Vec::with_capacity(HEADER as usize + 64 * matrices.len());
            bytes.extend_from_slice(bytemuck::cast_slice(&matrices[..2]));
            bytes.extend_from_slice(bytemuck::cast_slice(&deformed));
            let depth_rows = depth_before(&previous.0, size, convention);
            bytes.extend_from_slice(bytemuck::cast_slice(&depth_rows));
            bytes.extend_from_slice(bytemuck::cast_slice(&matrices[2..]));
            resources.queue.write_buffer(&state.matrices, 0, &bytes);
            let key = Key {
                convention,
                ids: match self.surfaces {
                    Surfaces::Ids(ids) => Some(resources.shape(ids).format),
                    Surfaces::Depth(_) | Surfaces::Meshes(..) => None,
                },
            };
            let (module, layout) = (&state.pass.module, &state.pass.layout);
            let pipeline = state.pass.pipelines.get(key, |key| {
                let mut constants = vec![
                    ("VIEW", f64::from(u8::from(self.view))),
                    ("FAR_DEPTH", f64::from(far_depth(key.convention))),
                ];
                if let Some(ids) = key.ids {
                    constants.push(("SPLIT_IDS", split_ids(ids)));
                }
                compute_pipeline(
                    device,
                    "motion vectors",
                    layout,
                    module,
                    "cs_motion",
                    &constants,
                )
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, scene.bind_group(convention), &[]);
            let positions = replaced.map_or(&state.no_positions, |p| &p.buffer);
            let owned: &[&wgpu::Buffer] = match self.surfaces.objects() {
                true => &[&state.matrices, positions],
                false => &[&state.matrices],
            };
            let group = state.pass.inputs.bind_group_with(resources, owned);
            pass.set_bind_group(1, &group, &[]);
            if self.surfaces.objects() {
                pass.set_bind_group(2, scene.geometry_group(device)?, &[]);
            }
            let out = resources.shape(self.target);
            pass.dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
            Ok(())
        }
    }

    /// motion.wgsl's `depth_before` and `w_before`: the rows of the inverse of
    /// `previous`'s clip matrix (for camera-relative points) whose products with a point
    /// in its clip space divide to the point's view depth along `previous`'s forward, in
    /// f64 as [`matrices`] are.
    fn depth_before(
        previous: &Camera,
        size: (u32, u32),
        convention: DepthConvention,
    ) -> [[f32; 4]; 2] {
        let back = view_projection(previous, size, convention)
            .as_dmat4()
            .inverse()
            .transpose();
        let forward = previous.forward().extend(0.0);
        [back * forward, back * DVec4::W].map(|row| row.as_vec4().to_array())
    }

    /// What the per-mesh matrices of motion.wgsl's `Motion` take points from.
    #[derive(Copy, Clone)]
    enum MeshSpace {
        /// The mesh's object space: a triangle rebuilt from the scene's geometry.
        Object,
        /// This frame's camera-relative space: a point a depth buffer holds.
        CameraRelative,
    }

    /// motion.wgsl's `Motion` for a frame of `size` drawn as `current` after `previous`
    /// (each a camera and the meshes' transforms), composed in f64 and only then cast:
    /// this frame's clip space from camera-relative points and the previous frame's from
    /// the same points standing still, then per mesh both frames' clip space from points
    /// in `space`. Without the jitter: gpu_scene's `view_projection`. From camera-relative
    /// space a point goes back to its mesh's object space through the inverse of this
    /// frame's transform; a mesh whose transform has no inverse (scaled to nothing) draws
    /// no pixel, and its points are taken to stand still.
    fn matrices(
        current: &(Camera, Vec<DMat4>),
        previous: &(Camera, Vec<DMat4>),
        size: (u32, u32),
        convention: DepthConvention,
        space: MeshSpace,
    ) -> Vec<[[f32; 4]; 4]> {
        let clip = |camera: &Camera| view_projection(camera, size, convention).as_dmat4();
        let (now, before) = (clip(&current.0), clip(&previous.0));
        let (eye, eye_before) = (current.0.position, previous.0.position);
        let still = before * DMat4::from_translation(eye - eye_before);
        let mut matrices = vec![now, still];
        for (mesh, &transform) in current.1.iter().enumerate() {
            let transform_before = previous.1.get(mesh).copied().unwrap_or(transform);
            let was = before * DMat4::from_translation(-eye_before) * transform_before;
            match space {
                MeshSpace::Object => {
                    matrices.push(now * DMat4::from_translation(-eye) * transform);
                    matrices.push(was);
                }
                MeshSpace::CameraRelative => {
                    // This frame's camera-relative space from the object's.
                    let placed = DMat4::from_translation(-eye) * transform;
                    let back = placed.inverse();
                    let moved = match placed.determinant() != 0.0 && back.is_finite() {
                        true => was * back,
                        false => still,
                    };
                    matrices.extend([now, moved]);
                }
            }
        }
        if current.1.is_empty() {
            matrices.extend([DMat4::IDENTITY; 2]);
        }
        matrices
            .iter()
            .map(|m| Mat4::to_cols_array_2d(&m.as_mat4()))
            .collect()
    }
}
