//! `shadow_maps`: the depth of the scene's opaque meshes seen from each shadowed light,
//! drawn by the hardware raster into one atlas texture, which the light passes read
//! through their `shadows` slot (common/shadows.rs).
//!
//! ```ron
//! (name: "shadow maps", plugin: "shadow_maps",
//!  when: "shadows",             // the scene's feature: a light emits and the host
//!                               // has not turned shadows off
//!  params: (slope_bias: 2.0,    // the default: the raster's slope-scaled depth bias
//!           clusters: culled),  // the default: each view draws the clusters it may see
//!  outputs: { "atlas": "shadow_atlas" })   // depth32float, square, 1 sample
//! ```
//!
//! The atlas holds one map per view: the cascades of a directional light (4), a point
//! light's cube faces (6), a spot light's perspective map (1), each a square from a
//! quarter of the atlas's side down to 1/32 of it, sized by its light's share of the
//! screen (`shadows::ATLAS_UNITS`). Which lights get them, how large,
//! and where each view looks is the scene's, each frame (gpu_scene/shadows.rs): this pass
//! writes the views for the frame's output and atlas size, then draws every opaque mesh
//! (vertices pulled from storage, as the visibility raster does) once per view into its
//! tile, only the runs of its clusters that may fall inside the view, depth only, standard Z, both faces, with a slope-scaled depth bias. The atlas is
//! cleared to the far plane; tiles without a view stay clear. Alpha MASK materials cast
//! only where their base colour alpha (factor, vertex colour and texture, from the
//! scene's texture table) reaches the cutoff, as they draw in the other passes.
//!
//! Given `shadow_raster`'s keys (`inputs: { "keys": .. }`, parts/shadow_maps_compute.ron)
//! the compute raster has drawn every other mesh this frame, with the views it wrote: the
//! pass draws the alpha MASK meshes alone, into a depth texture that `shadow_resolve`
//! merges with the keys into the atlas. The keys are read for that order, not bound.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::types::TextureFormat;
use rgraph_core::{AspectAccess, BufferHandle, PassBuilder, PassKind, TextureHandle};

use crate::common::plugin::Shared;
use crate::common::shadow_depth::{self, check_atlas, check_slope_bias, keys};
use crate::common::textures::{self, Want};
use crate::shaders;

pub struct ShadowMaps(pub(crate) Shared);

/// The maps' depth: the hardware's depth test keeps the nearest.
const DEPTH: &[TextureFormat] = &[TextureFormat::Depth32Float];

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowMapsParams {
    /// The raster's slope-scaled depth bias (wgpu's `DepthBiasState::slope_scale`): depth
    /// pushed away from the light in proportion to a triangle's depth slope, against the
    /// acne of surfaces the light grazes. shadow.wgsl's normal offset does the rest.
    #[serde(default = "shadow_depth::slope_bias")]
    pub slope_bias: f32,
    /// Without `keys`; with them the views are culled as `shadow_raster` culled them.
    #[serde(default)]
    pub clusters: ShadowClusters,
}

/// What each view of `shadow_maps` draws of a mesh.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadowClusters {
    /// The runs of its clusters whose boxes may fall inside the view (tested on the CPU
    /// each frame, gpu_scene/view_culling.rs): a cascade over part of a terrain, or a
    /// point light's face, draws that part. The default.
    #[default]
    Culled,
    /// All of it, in every view.
    Off,
}

/// The shadow maps' pass as set up: what its `gpu` module records.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct ShadowDraw {
    pub source: String,
    pub atlas: TextureHandle,
    pub slope_bias: f32,
    pub clusters: ShadowClusters,
    /// `shadow_raster`'s keys, where the file gives them (an optional read: absent
    /// where a condition drops that pass): with them the pass draws the alpha MASK
    /// meshes alone.
    pub keys: Option<BufferHandle>,
}

impl Plugin for ShadowMaps {
    const NAME: &'static str = "shadow_maps";
    type Params = ShadowMapsParams;

    fn kind(&self, _: &ShadowMapsParams) -> PassKind {
        PassKind::Render
    }

    fn setup(
        &self,
        params: ShadowMapsParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        check_slope_bias(params.slope_bias)?;
        let want = Want::new("the shadow atlas", DEPTH).samples(1);
        let (atlas, desc) = textures::output(slots, pass, "atlas", want, |pass, h, _| {
            pass.depth_stencil(h, AspectAccess::Clear(1.0), AspectAccess::Absent)
        })?;
        check_atlas(slots, "atlas", desc.size)?;
        let keys = match slots.kind("keys") {
            Some(_) => Some(keys(pass, slots, desc.size)?),
            None => None,
        };
        let draw = ShadowDraw {
            source: shaders::SHADOW_RASTER.compose(1)?.source().to_owned(),
            atlas,
            slope_bias: params.slope_bias,
            clusters: params.clusters,
            keys,
        };
        self.0.record(pass, draw);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording the shadow maps: the frame's views written, then per view its tile as
    //! viewport and every opaque mesh drawn, the view chosen by a dynamic offset into a
    //! small uniform buffer of view indices the pass owns.

    use std::sync::Arc;

    use super::{ShadowClusters, ShadowDraw};
    use crate::common::gpu::pipeline::{module, pipeline_layout, PipelineDesc};
    use crate::common::gpu::{Frame, Recorded, Recorder, Render};
    use crate::gpu_scene::{GpuScene, MeshRuns, ShadowOptions};
    use crate::shadows::SHADOW_VIEWS;
    use rgraph_scene::DepthConvention;
    use wgpu::util::DeviceExt;

    /// The atlas's depth test and write: the nearer depth stays, `bias` added.
    fn nearer_depth(bias: wgpu::DepthBiasState) -> wgpu::DepthStencilState {
        wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias,
        }
    }

    pub(crate) struct State {
        pipeline: wgpu::RenderPipeline,
        /// For alpha MASK materials: the cutoff tested per fragment.
        masked: wgpu::RenderPipeline,
        /// View `v`'s index at `v * stride`, bound with that dynamic offset.
        views: wgpu::BindGroup,
        stride: u32,
    }

    /// Draws into the atlas tile `(x, y, side)` (texels) alone: viewport and scissor.
    fn set_tile(pass: &mut wgpu::RenderPass<'_>, (x, y, side): (u32, u32, u32)) {
        pass.set_viewport(x as f32, y as f32, side as f32, side as f32, 0.0, 1.0);
        pass.set_scissor_rect(x, y, side, side);
    }

    impl Recorder for ShadowDraw {
        type Stage = Render;
        type Scene = Arc<GpuScene>;
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let (device, scene) = (frame.device, &frame.scene);
            let stride = device.limits().min_uniform_buffer_offset_alignment.max(16);
            let mut indices = vec![0u8; (stride * SHADOW_VIEWS) as usize];
            for v in 0..SHADOW_VIEWS {
                let at = (v * stride) as usize;
                indices[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadow view indices"),
                contents: &indices,
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let view_layout = crate::kept::bind_group_layout(
                device,
                "shadow view index",
                &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: true,
                        min_binding_size: wgpu::BufferSize::new(16),
                    },
                    count: None,
                }],
            );
            let views = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("shadow view index"),
                layout: &view_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(16),
                    }),
                }],
            });
            let layout = pipeline_layout(
                device,
                &[
                    Some(scene.layout()),
                    Some(&view_layout),
                    Some(scene.geometry_layout()),
                    Some(scene.texture_table_layout()),
                ],
            );
            let module = module(device, "shadow maps", &self.source);
            let pipeline = |vertex, fragment| {
                PipelineDesc {
                    label: "shadow maps",
                    layout: &layout,
                    module: &module,
                    vertex,
                    buffers: &[],
                    fragment,
                    constants: &[],
                    targets: &[],
                    // Both faces: open meshes (a ground plane) and closed ones cast alike.
                    cull: None,
                    depth_stencil: Some(nearer_depth(wgpu::DepthBiasState {
                        constant: 0,
                        slope_scale: self.slope_bias,
                        clamp: 0.0,
                    })),
                    samples: 1,
                    mask: !0,
                }
                .build(device)
            };
            Ok(State {
                pipeline: pipeline("vs_shadow", "fs_shadow"),
                masked: pipeline("vs_shadow_masked", "fs_shadow_masked"),
                views,
                stride,
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device, scene) = (frame.resources, frame.device, &frame.scene);
            let atlas = resources.shape(self.atlas);
            // With the compute raster's keys, it drew all but the alpha MASK meshes.
            let keys = self.keys.filter(|keys| resources.has(*keys));
            let (size, side) = (resources.output_size(), atlas.width);
            let work = match keys {
                // The work `shadow_raster` made this frame.
                Some(_) => scene.compute_shadow_work(size, side).ok_or(
                    "shadow_raster, which writes the keys, made no shadow work this frame",
                )?,
                None => {
                    let options = ShadowOptions {
                        culled: self.clusters == ShadowClusters::Culled,
                        small_texels: None,
                    };
                    scene.shadow_work(resources.queue, size, side, options)
                }
            };
            // The views take camera-relative positions; group 0's camera is not read.
            pass.set_bind_group(0, scene.bind_group(DepthConvention::Standard), &[]);
            pass.set_bind_group(2, scene.geometry_group(device)?, &[]);
            // Textured alpha masks read the table.
            let table = frame.scenes.texture_table(scene, device, resources.queue)?;
            pass.set_bind_group(3, table, &[]);
            scene.bind_indices(pass);
            for (view, work) in (0u32..).zip(&work.views) {
                set_tile(pass, work.tile);
                pass.set_bind_group(1, &state.views, &[view * state.stride]);
                let drawn = |m: &&MeshRuns| keys.is_none() || m.masked;
                for mesh in work.meshes.iter().filter(drawn) {
                    pass.set_pipeline(match mesh.masked {
                        true => &state.masked,
                        false => &state.pipeline,
                    });
                    let instances = mesh.instance..mesh.instance + 1;
                    for run in &mesh.runs.large {
                        pass.draw_indexed(mesh.indices(run), mesh.base_vertex, instances.clone());
                    }
                }
            }
            Ok(())
        }
    }
}
