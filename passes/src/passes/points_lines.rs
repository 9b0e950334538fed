//! `points_lines`: the scene's glTF points and lines ([`rgraph_scene::PointsLines`]),
//! drawn after the opaque scene is lit, into an accumulation target that
//! `composite_transparent` blends onto the resolved HDR image, so that every pipeline
//! (G-buffer, visibility buffer in hardware or in compute, forward, 1x or 4x) draws them
//! alike.
//!
//! ```ron
//! (name: "points lines", plugin: "points_lines",
//!  params: (point_size: 3.0),     // a point's side in pixels (the default); reversed_z optional
//!  inputs: { "depth": "depth" },  // the opaque passes' depth, any sample count: read-only
//!  outputs: { "accum": "points_lines" }),   // rgba16float, the depth's sample count
//! (name: "composite points lines", plugin: "composite_transparent",
//!  inputs: { "accum": "points_lines", "resolved": "resolved_hdr" },
//!  outputs: { "resolved": "resolved" })
//! ```
//!
//! **Drawing.** Lines are a line list (glTF LINE_LOOP and LINE_STRIP are loaded as
//! lists) one pixel wide, as the rasteriser draws them; points are squares of
//! `point_size` pixels facing the screen at the point's depth, expanded in the vertex
//! shader from an instanced quad (six vertices a point: wgpu draws a point list one
//! pixel wide and has no point size). With several samples per pixel the rasteriser
//! covers each sample inside the line's or square's area, and the composite averages
//! them: the multisampling anti-aliases them. Both are tested against the opaque
//! passes' depth, attached read-only (the opaque surfaces hide them per sample; they hide
//! nothing, not even each other: they are opaque and of one colour each, so what they
//! cover of each other matters only where colours differ).
//!
//! **Shading.** Unlit, as the glTF sample viewer draws points and lines: the material's
//! base colour factor times COLOR_0, plus its emission. Textures are not sampled (points
//! and lines have no texture coordinates worth a lookup in glTF practice) and alpha is
//! ignored. Each vertex's colour is computed once, on the CPU, when the pass is first
//! recorded on a device, and kept with its object-space position and its primitive's
//! index: 28 bytes a drawn vertex (a point takes one, a segment two).
//!
//! **Placement.** Each primitive is where the frame inputs put it
//! ([`FrameInputs::points_lines`]: the scene's rest transforms, or an animation's pose,
//! or an engine's): the vertex shader applies its primitive's matrix, object space to
//! world space minus an anchor at the centre of the scene's bounds (composed in f64, so
//! that f32 keeps its precision near the scene), then the anchor's camera-relative
//! position. The pass rewrites the matrices (64 bytes a primitive) in a frame whose
//! transforms differ from those it last wrote, and only then; the vertices are never
//! rewritten. Skins and morph targets do not deform points and lines (the loader warns).
//!
//! **The accumulation** begins as (0, 0, 0, 1) (a clear) and each covered sample
//! becomes (colour, 0): colour over black and transmittance 0, as the transparent pass
//! leaves an opaque surface, so `composite_transparent` gives `resolved * (1 - c) + c *
//! colour` for a pixel of coverage `c`, over the rectangle the blended meshes and the
//! points and lines may cover ([`GpuScene::blended_rect`]).
//!
//! [`GpuScene::blended_rect`]: crate::gpu_scene::GpuScene::blended_rect
//! [`FrameInputs::points_lines`]: crate::FrameInputs::points_lines

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{AspectAccess, ColorLoad, PassBuilder, PassKind, TextureHandle};

use super::forward::DEPTH;
use super::gbuffer::opaque_black;
use crate::common::depth::DepthRule;
use crate::common::plugin::Shared;
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct PointsLinesPass(pub(crate) Shared);

/// The largest `point_size`, in pixels: larger squares are not points any more.
const MAX_POINT_SIZE: f32 = 64.0;

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointsLinesParams {
    /// A point's side in pixels of the target, from 0 (exclusive) to 64.
    #[serde(default = "default_point_size")]
    pub point_size: f32,
    /// Fixes the depth convention; left out, it follows the depth format the compile
    /// picks, as the opaque passes' does: they must agree.
    #[serde(default)]
    pub reversed_z: Option<bool>,
}

/// Three pixels: an odd side centres a point on its pixel, which it covers with the
/// eight around it.
fn default_point_size() -> f32 {
    3.0
}

/// What the recording needs from the setup.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
struct Draw {
    source: String,
    depth_rule: DepthRule,
    point_size: f32,
    accum: TextureHandle,
    depth: TextureHandle,
}

impl Plugin for PointsLinesPass {
    const NAME: &'static str = "points_lines";
    type Params = PointsLinesParams;

    fn kind(&self, _: &PointsLinesParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: PointsLinesParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(params.point_size > 0.0 && params.point_size <= MAX_POINT_SIZE) {
            return Err(PluginError::Invalid(format!(
                "point_size must be more than 0 and at most {MAX_POINT_SIZE} pixels, got {}",
                params.point_size
            )));
        }
        let want = Want::new("the opaque passes' depth", DEPTH);
        let (depth, desc) = textures::input(slots, pass, "depth", want)?;
        pass.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
        let want =
            Want::new("the points' and lines' accumulation", textures::HDR).samples(desc.samples);
        let clear = ColorLoad::Clear(opaque_black());
        let (accum, _) = textures::attached_output(slots, pass, "accum", want, clear)?;
        let source = shaders::POINTS_LINES.compose(desc.samples)?;
        let draw = Draw {
            source: source.source().to_owned(),
            depth_rule: DepthRule::new(params.reversed_z),
            point_size: params.point_size,
            accum,
            depth,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use std::sync::Arc;

    use glam::{DMat4, DVec3, Vec3};
    use rgraph_scene::{DepthConvention, Scene, Topology};
    use wgpu::util::DeviceExt;

    use super::Draw;
    use crate::common::gpu::pipeline::{module, pipeline_layout, PipelineDesc, Pipelines};
    use crate::common::gpu::scene_draw::depth_test;
    use crate::common::gpu::{Frame, Recorded, Recorder, Render};
    use crate::gpu_scene::{GpuScene, Layer};

    /// One drawn vertex: object-space position, final linear colour, and the index of its
    /// primitive in `Scene::points_lines` (which picks its matrix).
    #[repr(C)]
    #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
    struct StrokeVertex {
        position: [f32; 3],
        color: [f32; 3],
        primitive: u32,
    }

    /// `Placement` in points_lines.wgsl.
    #[repr(C)]
    #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
    struct Placement {
        anchor: [f32; 3],
        point_size: f32,
        target_size: [f32; 2],
        _pad: [f32; 2],
    }

    /// The vertices' layout: per vertex for lines, per instance for points.
    fn vertex_layout(step_mode: wgpu::VertexStepMode) -> wgpu::VertexBufferLayout<'static> {
        const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32];
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<StrokeVertex>() as u64,
            step_mode,
            attributes: &ATTRIBUTES,
        }
    }

    /// The scene's points, then its segments' ends, as drawn vertices, and how many are
    /// points.
    fn strokes(scene: &Scene) -> (Vec<StrokeVertex>, u32) {
        let mut points = Vec::new();
        let mut lines = Vec::new();
        for (primitive, item) in (0..).zip(&scene.points_lines) {
            let material = &scene.materials[item.material];
            let base = Vec3::from_slice(&material.base_color_factor[..3]);
            let emission = Vec3::from_array(material.emission());
            let list = match item.topology {
                Topology::Points => &mut points,
                Topology::Lines => &mut lines,
            };
            list.extend(item.indices.iter().map(|&i| {
                let color = Vec3::from_slice(&item.colors[i as usize][..3]);
                StrokeVertex {
                    position: item.positions[i as usize],
                    color: (base * color + emission).to_array(),
                    primitive,
                }
            }));
        }
        let point_count = points.len() as u32;
        points.extend(lines);
        (points, point_count)
    }

    /// Each primitive's matrix for the shader: `transforms[i]`, then minus `anchor`,
    /// composed in f64.
    fn matrices(transforms: &[DMat4], anchor: DVec3) -> Vec<[[f32; 4]; 4]> {
        let to_anchor = DMat4::from_translation(-anchor);
        (transforms.iter())
            .map(|t| (to_anchor * *t).as_mat4().to_cols_array_2d())
            .collect()
    }

    #[derive(Clone, PartialEq)]
    pub(super) struct Key {
        topology: Topology,
        accum: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
        samples: u32,
        convention: DepthConvention,
    }

    pub(super) struct State {
        module: wgpu::ShaderModule,
        layout: wgpu::PipelineLayout,
        /// `None` for a scene without points or lines (the pass then draws nothing).
        vertices: Option<wgpu::Buffer>,
        anchor: DVec3,
        points: u32,
        /// Points and segment ends.
        total: u32,
        placement: wgpu::Buffer,
        /// One matrix per primitive (points_lines.wgsl's `models`).
        models: wgpu::Buffer,
        /// The transforms `models` holds (empty before the first frame writes them).
        placed: Vec<DMat4>,
        group: wgpu::BindGroup,
        pipelines: Pipelines<Key>,
    }

    impl Recorder for Draw {
        type Stage = Render;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let device = frame.device;
            let host = frame.scenes.scene().ok_or("points and lines: no scene")?;
            let (vertices, points) = strokes(host);
            let total = vertices.len() as u32;
            let vertices = (!vertices.is_empty()).then(|| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("points and lines"),
                    contents: bytemuck::cast_slice(&vertices),
                    usage: wgpu::BufferUsages::VERTEX,
                })
            });
            let buffer = |label, size: usize, usage| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: size as u64,
                    usage: usage | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            let placement = buffer(
                "points and lines placement",
                std::mem::size_of::<Placement>(),
                wgpu::BufferUsages::UNIFORM,
            );
            // wgpu refuses an empty storage binding: a scene without points or lines
            // (which draws nothing) binds one matrix.
            let models = buffer(
                "points and lines matrices",
                host.points_lines.len().max(1) * 64,
                wgpu::BufferUsages::STORAGE,
            );
            let entry =
                |binding, ty| crate::kept::buffer_entry(binding, wgpu::ShaderStages::VERTEX, ty);
            let group_layout = crate::kept::bind_group_layout(
                device,
                "points and lines placement",
                &[
                    entry(0, wgpu::BufferBindingType::Uniform),
                    entry(1, wgpu::BufferBindingType::Storage { read_only: true }),
                ],
            );
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("points and lines placement"),
                layout: &group_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: placement.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: models.as_entire_binding(),
                    },
                ],
            });
            let layouts = [Some(frame.scene.layout()), Some(&group_layout)];
            Ok(State {
                module: module(device, "points and lines", &self.source),
                layout: pipeline_layout(device, &layouts),
                vertices,
                anchor: host.bounds.center(),
                points,
                total,
                placement,
                models,
                placed: Vec::new(),
                group,
                pipelines: Pipelines::default(),
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let Some(vertices) = &state.vertices else {
                return Ok(());
            };
            let (pass, resources, scene) = (&mut *frame.pass, frame.resources, &frame.scene);
            let accum = resources.shape(self.accum);
            let depth = resources.shape(self.depth);
            let convention = self.depth_rule.convention(depth.format);
            let queue = resources.queue;
            let inputs = scene.inputs();
            if inputs.points_lines != state.placed {
                let models = matrices(&inputs.points_lines, state.anchor);
                queue.write_buffer(&state.models, 0, bytemuck::cast_slice(&models));
                state.placed.clone_from(&inputs.points_lines);
            }
            // Camera-relative, in f64 before the cast, as the scene's model matrices are.
            let anchor = state.anchor - inputs.camera.position;
            let placement = Placement {
                anchor: anchor.as_vec3().to_array(),
                point_size: self.point_size,
                target_size: [accum.width as f32, accum.height as f32],
                _pad: [0.0; 2],
            };
            queue.write_buffer(&state.placement, 0, bytemuck::bytes_of(&placement));
            pass.set_bind_group(0, scene.bind_group(convention), &[]);
            pass.set_bind_group(1, &state.group, &[]);
            pass.set_vertex_buffer(0, vertices.slice(..));
            let draws = [
                (Topology::Points, state.points),
                (Topology::Lines, state.total - state.points),
            ];
            for (topology, count) in draws {
                if count == 0 {
                    continue;
                }
                let key = Key {
                    topology,
                    accum: accum.format,
                    depth: depth.format,
                    samples: depth.samples,
                    convention,
                };
                let (module, layout) = (&state.module, &state.layout);
                let pipeline = state
                    .pipelines
                    .get(key, |key| build(frame.device, module, layout, key));
                pass.set_pipeline(pipeline);
                match topology {
                    Topology::Points => pass.draw(0..6, 0..count),
                    Topology::Lines => pass.draw(state.points..state.total, 0..1),
                }
            }
            Ok(())
        }
    }

    /// The pipeline of `key`: replacing the accumulation's colour, tested against the
    /// opaque depth without writing it.
    fn build(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        layout: &wgpu::PipelineLayout,
        key: &Key,
    ) -> wgpu::RenderPipeline {
        let (vertex, step_mode, topology) = match key.topology {
            Topology::Points => (
                "vs_point",
                wgpu::VertexStepMode::Instance,
                wgpu::PrimitiveTopology::TriangleList,
            ),
            Topology::Lines => (
                "vs_line",
                wgpu::VertexStepMode::Vertex,
                wgpu::PrimitiveTopology::LineList,
            ),
        };
        let targets = [Some(wgpu::ColorTargetState::from(key.accum))];
        PipelineDesc {
            label: "points and lines",
            layout,
            module,
            vertex,
            buffers: &[Some(vertex_layout(step_mode))],
            fragment: "fs_stroke",
            constants: &[],
            targets: &targets,
            cull: None,
            depth_stencil: Some(depth_test(key.depth, key.convention, Layer::Blended, false)),
            samples: key.samples,
            mask: !0,
        }
        .build_as(device, topology)
    }
}
