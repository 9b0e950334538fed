//! Recording a light pass: the full-screen draw for directional lights and ambient, then
//! each point or spot light's volume, once (per pixel or `sample_index`) or once per
//! sample with the multisample mask (`sample_mask`).
//!
//! Pipelines are made on first use, so a pass builds the full-screen one only when some
//! directional light emits or there is ambient, and volume ones only when a point or
//! spot light does ([`GpuScene::has_fullscreen_lights`], [`GpuScene::volume_lights`]);
//! each is compiled for the scene's light kinds (its shader variant, analysis/variant.rs),
//! which the key holds.

use std::sync::Arc;

use graph_core::gpu::RenderContext;

use crate::analysis::{GatedShader, Variant};
use crate::common::depth::far_depth;
use crate::common::gpu::{additive, per_scene, InputPass, PipelineDesc, EDGE_STENCIL};
use crate::gpu_scene::{volumes, SceneCache};
use crate::passes::light::{EdgeMode, Frequency, LightDraw, PixelSamples};
use crate::scene::DepthConvention;

/// What a light draw rasterizes, and so its depth test and culling.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Geometry {
    /// A full-screen triangle at the far plane: passes wherever geometry was drawn. For
    /// directional lights and ambient, or (`light` true) one point or spot light.
    FarPlane { light: bool },
    /// A volume's front faces, in front of the surface.
    FrontFaces,
    /// A volume's back faces, behind the surface (the camera may be inside). Never where
    /// they may reach beyond a finite far plane: the light is drawn full screen there.
    BackFaces,
}

#[derive(Clone, PartialEq)]
struct Key {
    hdr: wgpu::TextureFormat,
    depth: wgpu::TextureFormat,
    samples: u32,
    geometry: Geometry,
    /// `sample_mask` mode: the one sample the pipeline shades and writes.
    sample: Option<u32>,
    variant: Variant,
}

pub(crate) fn record(
    draw: LightDraw,
    scenes: Arc<SceneCache>,
) -> Box<dyn FnMut(&mut RenderContext<'_, '_>)> {
    let mut state = None;
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        let Some(scene) = scenes.for_frame(resources) else {
            return;
        };
        let size = resources.output_size();
        let state = per_scene(&mut state, &scene, || {
            InputPass::new(resources, "light", &draw.source, Some(&scene), &draw.inputs)
        });
        let (hdr, depth) = (resources.shape(draw.hdr), resources.shape(draw.depth));
        let passes: Vec<Option<u32>> = match draw.frequency {
            Frequency::Sample(EdgeMode::SampleMask) => (0..hdr.samples).map(Some).collect(),
            Frequency::Pixel(_) | Frequency::Sample(EdgeMode::SampleIndex) => vec![None],
        };
        let convention = draw.depth_rule.convention(depth.format);
        ctx.pass
            .set_bind_group(0, scene.bind_group(convention), &[]);
        ctx.pass
            .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
        ctx.pass.set_stencil_reference(EDGE_STENCIL);
        let (module, layout) = (&state.module, &state.layout);
        let variant = scenes.variant(GatedShader::Light);
        let mut use_pipeline = |pass: &mut wgpu::RenderPass<'_>, geometry, sample| {
            let key = Key {
                hdr: hdr.format,
                depth: depth.format,
                samples: hdr.samples,
                geometry,
                sample,
                variant: variant.clone(),
            };
            let pipeline = state.pipelines.get(key, |key| {
                let mut constants = vec![
                    ("FAR_DEPTH", f64::from(far_depth(convention))),
                    ("SAMPLE", f64::from(key.sample.unwrap_or(0))),
                ];
                constants.extend(key.variant.constants());
                let volume_buffers = [Some(volumes::VERTEX_LAYOUT)];
                PipelineDesc {
                    label: "light",
                    layout,
                    module,
                    vertex: match key.geometry {
                        Geometry::FarPlane { light: false } => "vs_directional",
                        Geometry::FarPlane { light: true } => "vs_fullscreen_light",
                        Geometry::FrontFaces | Geometry::BackFaces => "vs_volume",
                    },
                    buffers: match key.geometry {
                        Geometry::FarPlane { .. } => &[],
                        Geometry::FrontFaces | Geometry::BackFaces => &volume_buffers,
                    },
                    fragment: match (draw.frequency, key.sample) {
                        (Frequency::Pixel(PixelSamples::First), _) => "fs_pixel",
                        (Frequency::Pixel(PixelSamples::Average), _) => "fs_pixel_average",
                        (Frequency::Sample(_), None) => "fs_sample",
                        (Frequency::Sample(_), Some(_)) => "fs_one_sample",
                    },
                    constants: &constants,
                    targets: &[Some(additive(key.hdr))],
                    cull: match key.geometry {
                        Geometry::FarPlane { .. } => None,
                        Geometry::FrontFaces => Some(wgpu::Face::Back),
                        Geometry::BackFaces => Some(wgpu::Face::Front),
                    },
                    depth_stencil: Some(depth_stencil(key, convention, draw.frequency)),
                    samples: key.samples,
                    mask: key.sample.map_or(!0, |s| 1 << s),
                }
                .build(device)
            });
            pass.set_pipeline(pipeline);
        };
        for sample in passes {
            if scene.has_fullscreen_lights() {
                use_pipeline(ctx.pass, Geometry::FarPlane { light: false }, sample);
                ctx.pass.draw(0..3, 0..1);
            }
            for light in scene.volume_lights() {
                let instance = light.index..light.index + 1;
                let geometry = if !draw.volumes {
                    Geometry::FarPlane { light: true }
                } else if !scene.camera_may_be_inside(light, size) {
                    Geometry::FrontFaces
                } else if scene.far_plane_may_cut(light) {
                    // Its back faces would be clipped away beyond the far plane.
                    Geometry::FarPlane { light: true }
                } else {
                    Geometry::BackFaces
                };
                use_pipeline(ctx.pass, geometry, sample);
                if geometry == (Geometry::FarPlane { light: true }) {
                    ctx.pass.draw(0..3, instance);
                    continue;
                }
                let mesh = scene.volume_mesh(light.shape);
                ctx.pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                ctx.pass
                    .set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                ctx.pass
                    .draw_indexed(0..mesh.index_count, 0, light.index..light.index + 1);
            }
        }
    })
}

/// Read-only depth and stencil: the depth test per [`Geometry`], and the stencil test
/// that splits edge pixels (0x80) from the rest.
fn depth_stencil(
    key: &Key,
    convention: DepthConvention,
    frequency: Frequency,
) -> wgpu::DepthStencilState {
    use wgpu::CompareFunction as C;
    let reversed = convention == DepthConvention::ReversedZ;
    // "In front of" is Greater with reversed Z, Less without.
    let (in_front, behind) = match reversed {
        true => (C::GreaterEqual, C::LessEqual),
        false => (C::LessEqual, C::GreaterEqual),
    };
    let depth_compare = match key.geometry {
        // The far plane is behind every drawn surface, and no surface is behind it.
        Geometry::FarPlane { .. } => match reversed {
            true => C::Less,
            false => C::Greater,
        },
        Geometry::FrontFaces => in_front,
        Geometry::BackFaces => behind,
    };
    let test = wgpu::StencilFaceState {
        compare: match frequency {
            Frequency::Pixel(_) => C::NotEqual,
            Frequency::Sample(_) => C::Equal,
        },
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: wgpu::StencilOperation::Keep,
        pass_op: wgpu::StencilOperation::Keep,
    };
    wgpu::DepthStencilState {
        format: key.depth,
        depth_write_enabled: Some(false),
        depth_compare: Some(depth_compare),
        stencil: wgpu::StencilState {
            front: test,
            back: test,
            read_mask: EDGE_STENCIL,
            write_mask: 0,
        },
        bias: Default::default(),
    }
}
