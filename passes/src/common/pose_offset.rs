//! A G-buffer's pose offset: per sample, where the point it holds was in the last pose of
//! its mesh's skin or morph targets, from where it is now, in world space (rgba16float,
//! 8 bytes per sample, alpha unused: `textures::POSE_OFFSET`). A depth buffer's point
//! has no triangle to take back to the last pose, so the G-buffer pass
//! ([`gbuffer`](crate::passes::gbuffer)) writes it where it still has one: its vertex
//! stage reads where the deformation found each vertex (the positions its dispatch
//! replaced, gpu_scene/last_pose.rs) and turns the difference by the mesh's transform,
//! the fragment stage writes it at sample 0's position (the derivatives take it there
//! from the pixel's centre, where it is interpolated). Motion vectors
//! ([`motion_vectors`](crate::passes::motion_vectors)) add it to sample 0's point before
//! the mesh's previous transform and camera take the point back.
//!
//! The shipped files declare the target only for scenes with deformations (feature
//! `deformed`) and list the slots `optional`, in both passes: a scene without them keeps
//! the G-buffer, passes and images it had without the target. Each pass is made per
//! frame for whether its plan keeps the target (common/optional_targets.rs), with the
//! WGSL here for either.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{PassBuilder, TextureHandle};

use super::textures::{self, Input, Want};
use crate::shaders;

/// The slot that holds it, in the passes that write and read it.
pub(crate) const SLOT: &str = "pose_offset";

/// Where motion_pose.wgsl binds it (group 1).
const BINDING: u32 = 2;

/// What the target is, in messages.
pub(crate) const WHAT: &str = "the G-buffer's pose offset";

/// gbuffer.wgsl's `last_pose`: where the deformation had each vertex, where the pass
/// `writes` the target; else where it is (so the offset is zero, and unwritten).
pub(crate) fn last_pose_wgsl(writes: bool) -> &'static str {
    match writes {
        true => shaders::GBUFFER_LAST_POSE,
        false => {
            "// Generated: no pose offset is written (common/pose_offset.rs).\n\
             fn last_pose(index: u32, position: vec3<f32>) -> vec3<f32> {\n\
             \x20   return position;\n}\n"
        }
    }
}

/// motion_meshes.wgsl's `last_pose_offset`: the target's, where the pass `reads` it; else
/// none, so a deformed mesh's points move with its transform alone.
pub(crate) fn offset_wgsl(reads: bool) -> &'static str {
    match reads {
        true => shaders::MOTION_POSE,
        false => {
            "// Generated: no pose offset is read (common/pose_offset.rs).\n\
             fn last_pose_offset(pixel: vec2<i32>) -> vec3<f32> {\n\
             \x20   return vec3<f32>(0.0);\n}\n"
        }
    }
}

/// Declares the pose offset sampled where the file gives a pass reading a G-buffer of
/// `samples` its slot, and adds it to `inputs` at motion_pose.wgsl's binding.
pub(crate) fn input(
    slots: &mut Slots<'_>,
    pass: &mut PassBuilder<'_>,
    samples: u32,
    inputs: &mut Vec<Input>,
) -> Result<Option<TextureHandle>, PluginError> {
    if slots.kind(SLOT).is_none() {
        return Ok(None);
    }
    let want = Want::new(WHAT, textures::POSE_OFFSET).samples(samples);
    let (input, _) = textures::sampled(slots, pass, SLOT, want, BINDING)?;
    inputs.push(input);
    Ok(Some(input.texture))
}
