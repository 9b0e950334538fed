//! `taa`: temporal anti-aliasing. Each frame's camera is jittered by a point of the
//! Halton(2, 3) sequence (16 a cycle, gpu_scene/jitter.rs), so over frames a pixel is
//! sampled all over; this pass blends the frame into its own previous result, reprojected
//! with the motion vectors (`motion_vectors`) through a Catmull-Rom filter and clipped to
//! the frame's neighbourhood in YCoCg, which is what keeps a moved surface from leaving a
//! ghost (wgsl/taa.wgsl).
//!
//! ```ron
//! (name: "taa", plugin: "taa",
//!  params: (history_weight: 0.9,      // in [0, 1): the most the history weighs
//!           motion_weight: 0.05,      // the frame's least weight per pixel of motion
//!           samples: 4),              // the image's samples per pixel (default 1)
//!  inputs: {
//!      "hdr": "resolved",             // rgba16float, 1 sample: this frame, resolved
//!      "motion": "motion",            // motion_vectors' output
//!      "history": "taa_prev",         // History(of: "taa"): this pass's last output
//!      "motion_history": "motion_prev", // History(of: "motion"), optional
//!  },
//!  outputs: { "resolved": "taa" })    // rgba16float, 1 sample: what tone mapping reads
//! ```
//!
//! After a reset of the history (the first frame, a resize, a change of plan,
//! `Executor::reset_history`) the frame is taken alone; the n-th frame after weighs 1 / n,
//! so a still image averages its frames evenly, until 1 / n falls to 1 - `history_weight`,
//! from which the history weighs `history_weight` (an exponential average: more keeps
//! more of the past, smoother and slower to follow change; 0.9, the default, weighs about
//! the last 10 frames). A still camera's image therefore converges to the average of the
//! frame read at the pixel's centre over the jitter's cycle: the scene filtered by the
//! Catmull-Rom kernel (below) rather than by the pixel's box, as the 16-sample
//! reference's is, which on lavapipe's test scene brings the edges closer to the
//! reference and the flat shading a little further (tests/temporal_aa.rs).
//!
//! Where the image moves, the frame weighs at least `motion_weight` per pixel of motion
//! (velocity-weighted feedback): a moving history is resampled every frame, each time a
//! little blurrier, and what the clamp lets through of a moving edge lags behind it, so
//! the faster a pixel moves the less of its past it keeps. The motion a pixel is
//! reprojected by is the front-most surface's of its 3 x 3 neighbourhood (by the view
//! depth `motion_vectors` keeps in the motion's blue), so the pixels about a moving
//! silhouette, whose centres may see the surface behind, follow the edge.
//!
//! Where the file gives `motion_history`, the previous frame's motion, the history is
//! rejected where it shows a surface that hid the pixel's point (a moving object
//! uncovering what is behind), which the neighbourhood's clamp lets through wherever
//! this frame's neighbourhood spans a wide box (a shaded or textured surface): of the
//! texels the reprojected point's bilinear footprint weighs, those whose surface was
//! more than 2% (plus the surface's slope over a pixel) nearer than the point was then
//! (the motion's alpha) and moved more than 2 pixels apart from it; the frame weighs at
//! least their share, all of it where the footprint lies wholly on the hiding surface
//! (wgsl/taa_disocclusion.wgsl). Its cost is the motion's history (one more rgba16float
//! texture, 8 bytes a pixel, and the motion kept apart from transient memory) and four
//! texel loads a pixel; no pass or target written is added. Without it, the clamp alone
//! deals with uncovered surfaces.
//!
//! This frame's pixel is read where the output pixel's centre lies in the jittered image
//! (the jitter undone, through a Catmull-Rom filter): blended as drawn, a sample offset by
//! the jitter would displace a moving image by the weighted mean of the last few frames'
//! offsets, which a still image's even average over the cycle cancels but motion, where
//! the latest frames weigh most, does not.
//!
//! The jitter spans 1/√`samples` of a pixel: the whole pixel for one sample, half of it
//! for 4x MSAA, whose own samples already spread over the pixel (spanning the whole
//! pixel, 4x MSAA's footprint over frames would be a two-pixel tent, a blur).
//! The jitter is asked of the plugins' shared scene at setup: every pass of the file
//! draws with it, in plans that cull this pass too (a debug view of a TAA file is
//! jittered). The blend is in linear HDR before tone mapping, as MSAA's resolve and the
//! reference's average are.

use serde::Deserialize;

use rgraph_core::file::{Plugin, PluginError, Slots};
use rgraph_core::{Aspect, PassBuilder, PassKind, TextureHandle};

use crate::common::plugin::Shared;
use crate::common::textures::{self, Input, Texels, Want};
use crate::shaders;

pub struct Taa(pub(crate) Shared);

/// taa.wgsl's `hidden_share` where the pass is given no history of the motion.
const NO_DISOCCLUSION: &str = "// Generated: no history of the motion is read.\n\
    fn hidden_share(previous: vec2<f32>, depth_before: f32, slope: f32, motion: vec2<f32>) \
    -> f32 {\n\
    \x20   return 0.0;\n}\n";

#[derive(Clone, Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TaaParams {
    /// The most the history weighs, in [0, 1).
    pub history_weight: f32,
    /// The frame's least weight per pixel of the pixel's motion, at least 0.
    pub motion_weight: f32,
    /// Samples per pixel of the image filtered (MSAA's), which the jitter's span
    /// follows; 1, 2, 4 or 8.
    pub samples: u32,
}

impl Default for TaaParams {
    fn default() -> TaaParams {
        TaaParams {
            history_weight: 0.9,
            motion_weight: 0.05,
            samples: 1,
        }
    }
}

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct TaaDispatch {
    source: String,
    history_weight: f32,
    motion_weight: f32,
    history: TextureHandle,
    /// Group 1's textures (the motion's history at binding 4 where given), the output
    /// at binding 7.
    inputs: Vec<Input>,
    target: TextureHandle,
}

impl Plugin for Taa {
    const NAME: &'static str = "taa";
    type Params = TaaParams;

    fn kind(&self, _: &TaaParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: TaaParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        if !(0.0..1.0).contains(&params.history_weight) {
            return Err(PluginError::Invalid(format!(
                "history_weight is {}, but must be at least 0 and below 1 (the share of the \
                 image the history keeps each frame)",
                params.history_weight
            )));
        }
        if !(params.motion_weight >= 0.0 && params.motion_weight.is_finite()) {
            return Err(PluginError::Invalid(format!(
                "motion_weight is {}, but must be a finite number of at least 0 (the \
                 frame's least weight per pixel of motion)",
                params.motion_weight
            )));
        }
        if ![1, 2, 4, 8].contains(&params.samples) {
            return Err(PluginError::Invalid(format!(
                "samples is {}, but must be 1, 2, 4 or 8 (the image's samples per pixel)",
                params.samples
            )));
        }
        let one = |what| Want::new(what, textures::HDR).samples(1);
        let (current, _) = textures::sampled(slots, pass, "hdr", one("this frame's image"), 0)?;
        let (motion, _) = textures::sampled(slots, pass, "motion", one("the motion vectors"), 1)?;
        let (mut history, _) = textures::sampled(
            slots,
            pass,
            "history",
            one("the history (History(of: ..) of this pass's output)"),
            2,
        )?;
        history.texels = Texels::Filtered { sampler: 3 };
        let mut inputs = vec![current, motion, history];
        let disocclusion = match slots.kind("motion_history").is_some() {
            true => {
                let want = one("the motion's history (History(of: ..) of input \"motion\")");
                let (motion_history, _) =
                    textures::sampled(slots, pass, "motion_history", want, 4)?;
                inputs.push(motion_history);
                shaders::TAA_DISOCCLUSION
            }
            false => NO_DISOCCLUSION,
        };
        let want = one("the anti-aliased image");
        let (target, _) = textures::output(slots, pass, "resolved", want, |pass, h, _| {
            pass.storage_write(h)
        })?;
        inputs.push(Input {
            binding: 7,
            texture: target,
            aspect: Aspect::All,
            texels: Texels::Store,
        });
        let source = shaders::TAA
            .compose_with(1, disocclusion)?
            .source()
            .to_owned();
        #[cfg(feature = "gpu")]
        self.0
            .scenes
            .jitter_camera(1.0 / (params.samples as f32).sqrt());
        let dispatch = TaaDispatch {
            source,
            history_weight: params.history_weight,
            motion_weight: params.motion_weight,
            history: history.texture,
            inputs,
            target,
        };
        self.0.record(pass, dispatch);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    //! Recording: this frame's weights and jitter written into the pass's own buffer,
    //! then one dispatch of 8 x 8 pixels per workgroup.

    use super::TaaDispatch;
    use crate::common::gpu::{compute_pipeline, Compute, Frame, GroupBuffers, InputPass};
    use crate::common::gpu::{Recorded, Recorder};

    /// taa.wgsl's binding of `TaaFrame`.
    const FRAME_BINDING: u32 = 9;

    pub(crate) struct State {
        pass: InputPass<(), wgpu::ComputePipeline>,
        /// taa.wgsl's `TaaFrame`.
        frame: wgpu::Buffer,
        /// Frames blended since the history was last reset.
        frames: u32,
    }

    impl Recorder for TaaDispatch {
        type Stage = Compute;
        type Scene = ();
        type State = State;

        fn build(&self, frame: &Frame<'_, '_, Self>) -> Result<State, String> {
            let buffers = GroupBuffers {
                read: Vec::new(),
                owned: vec![FRAME_BINDING],
            };
            let resources = frame.resources;
            Ok(State {
                pass: InputPass::with_geometry(
                    resources,
                    "taa",
                    &self.source,
                    None,
                    &self.inputs,
                    &buffers,
                    false,
                ),
                frame: frame.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("taa frame"),
                    size: 16,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                frames: 0,
            })
        }

        fn record(&self, state: &mut State, frame: &mut Frame<'_, '_, Self>) -> Recorded {
            let pass = &mut *frame.pass;
            let (resources, device) = (frame.resources, frame.device);
            state.frames = match resources.history_reset(self.history) {
                true => 1,
                false => state.frames.saturating_add(1),
            };
            let weight = (1.0 / state.frames as f32).max(1.0 - self.history_weight);
            // The offset the scene's camera drew this frame with (SceneCache::for_frame).
            let jitter = frame.scenes.jitter_at(resources.frame());
            let bytes = [weight, self.motion_weight, jitter[0], jitter[1]];
            resources
                .queue
                .write_buffer(&state.frame, 0, bytemuck::cast_slice(&bytes));
            let (module, layout) = (&state.pass.module, &state.pass.layout);
            let pipeline = state.pass.pipelines.get((), |_| {
                compute_pipeline(device, "taa", layout, module, "cs_taa", &[])
            });
            pass.set_pipeline(pipeline);
            let group = state
                .pass
                .inputs
                .bind_group_with(resources, &[&state.frame]);
            pass.set_bind_group(1, &group, &[]);
            let out = resources.shape(self.target);
            pass.dispatch_workgroups(out.width.div_ceil(8), out.height.div_ceil(8), 1);
            Ok(())
        }
    }
}
