//! A pass that draws the scene's meshes, as the G-buffer, forward, transparent and light
//! pre-pass plugins set it up: one draw per mesh, a pipeline per material state. Its
//! recording (feature `gpu`) is `common/gpu/scene_draw.rs`.

use rgraph_core::TextureHandle;

use super::depth::DepthRule;
use super::textures::Input;
use crate::variant::GatedShader;

#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct SceneDraw {
    pub label: &'static str,
    pub shader: GatedShader,
    pub source: String,
    /// Resolved against the depth attachment's format when recording.
    pub depth_rule: DepthRule,
    /// Color attachments in location order.
    pub targets: Vec<TextureHandle>,
    pub depth: TextureHandle,
    pub stages: Stages,
    /// Draws the alpha BLEND meshes, back to front; else the opaque and MASK ones.
    pub blended: bool,
    /// Begins the targets over the rectangle the blended meshes may cover
    /// (`GpuScene::blended_rect`) with this fragment entry point of the pass's module
    /// (after common.wgsl's `vs_fullscreen`, writing every target, depth neither tested nor
    /// written), and keeps the meshes' draws to it; nothing is drawn when no blended mesh
    /// is in view. For targets the pass begins without a clear (the transparent
    /// accumulation with `extent: blended`), whose other pixels nothing reads.
    pub begin_blended: Option<&'static str>,
    /// After the meshes, fills what they left undrawn with the module's `fs_background`
    /// (common/background.rs): for targets begun without a clear, over a depth the pass
    /// cleared.
    pub fill_background: bool,
    /// Draws the opaque meshes again over the depth an earlier draw of the same shader
    /// module wrote (the light pre-pass's material pass): tested for the same or a nearer
    /// depth without writing it, reading these textures as group 2. The pass attaches the
    /// depth-stencil read-only.
    pub redraw: Option<Vec<Input>>,
    /// The shadow atlas the shader reads in group 2 too (common/shadows.rs), where the
    /// pass lights the meshes with shadows.
    pub shadows: Option<Input>,
    /// The vertex stage reads where the deformation had the vertices in the last pose,
    /// as group 3 (`GpuScene::last_pose_group`): the G-buffer's pose offset.
    pub last_pose: bool,
}

/// The entry points a pass draws meshes with.
#[derive(Copy, Clone)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct Stages {
    pub vertex: &'static str,
    pub fragment: &'static str,
    pub masked: Masked,
}

/// How a material with an alpha MASK is drawn.
#[derive(Copy, Clone)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) enum Masked {
    /// Through this fragment entry point instead.
    Entry(&'static str),
    /// Through the same ones, with the pipeline-overridable constant `MASKED` true (and
    /// false for the other materials).
    Constant,
}

impl SceneDraw {
    /// `label`'s draw of the opaque meshes into `targets` and `depth`: no blended
    /// beginning, no background fill, no redraw. A pass that needs more sets those fields
    /// over this (`SceneDraw { redraw, ..SceneDraw::new(...) }`).
    pub fn new(
        label: &'static str,
        shader: GatedShader,
        source: String,
        depth_rule: DepthRule,
        targets: Vec<TextureHandle>,
        depth: TextureHandle,
        stages: Stages,
    ) -> SceneDraw {
        SceneDraw {
            label,
            shader,
            source,
            depth_rule,
            targets,
            depth,
            stages,
            blended: false,
            begin_blended: None,
            fill_background: false,
            redraw: None,
            shadows: None,
            last_pose: false,
        }
    }
}
