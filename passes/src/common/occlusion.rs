//! Two-phase occlusion culling of the compute raster's clusters (Haar and Aaltonen,
//! "GPU-Driven Rendering Pipelines", SIGGRAPH 2015; as Bevy's meshlets and Nanite do it):
//! the slots `visibility_compute` takes for it. Its first phase bins the clusters that the
//! previous frame's depth pyramid does not hide and lists the others; `depth_pyramid`
//! builds a pyramid of what it drew; the second phase bins the listed clusters that this
//! pyramid does not hide, adding them to the first phase's keys; a last `depth_pyramid`
//! keeps the frame's pyramid, a history, for the next frame (cluster_occlusion.wgsl, and
//! why the image is exactly the one without it; docs/design/compute-raster.md).
//!
//! ```ron
//! resources: {
//!     "depth_pyramid": Texture(format: "r32float", size: Absolute(512, 512), mips: 10),
//!     "depth_pyramid_prev": History(of: "depth_pyramid"),
//!     "first_pyramid": Texture(format: "r32float", size: Absolute(512, 512), mips: 10),
//!     // 16 bytes of counts, then room for as many clusters as 4 bytes each fit.
//!     "occluded": Buffer(size: 4194320),
//! },
//! passes: [
//!     (name: "visibility", plugin: "visibility_compute",
//!      inputs: { "pyramid": "depth_pyramid_prev" },
//!      outputs: { "samples": "samples", "occluded": "occluded" }),
//!     (name: "depth pyramid (first phase)", plugin: "depth_pyramid",
//!      inputs: { "samples": "samples" }, outputs: { "pyramid": "first_pyramid" }),
//!     (name: "visibility (second phase)", plugin: "visibility_compute",
//!      inputs: { "samples": "samples", "pyramid": "first_pyramid", "occluded": "occluded" },
//!      outputs: { "samples": "keys", "occluded": "occlusion_counts" }),
//!     (name: "depth pyramid", plugin: "depth_pyramid",
//!      inputs: { "samples": "keys" }, outputs: { "pyramid": "depth_pyramid" }),
//! ]
//! ```
//!
//! A `visibility_compute` pass with a `pyramid` input is a phase: the second where it
//! modifies `samples` (and `occluded`, whose counts it completes), else the first, whose
//! `pyramid` must be a history. With `occlusion: false` (or 0: the shipped files give the
//! graph parameter `occlusion`) the first phase lists nothing and stores its keys as
//! `other_samples` says, the second records nothing, and so does `depth_pyramid`: the
//! raster of before, but for three empty passes. When the list is full, the first phase
//! draws what it would have listed.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{Buffer, BufferHandle, BufferRole, PassBuilder, TextureHandle};

use super::switch::Switch;
use super::textures::{self, Want};

/// The two passes of occlusion culling.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Phase {
    /// Tests every cluster against the previous frame's pyramid, and lists the hidden.
    First,
    /// Tests the listed clusters against the pyramid of what the first phase drew.
    Second,
}

/// A phase's slots, and whether it culls.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
#[derive(Copy, Clone, Debug)]
pub(crate) struct OcclusionSlots {
    pub phase: Phase,
    pub pyramid: TextureHandle,
    pub occluded: BufferHandle,
    pub on: bool,
}

/// Bytes before the list's entries: its count and the clusters the second phase drew
/// (cluster_occlusion.wgsl's OccludedClusters).
pub(crate) const LIST_HEADER: u64 = 16;

/// What the depth pyramid holds: the farthest depth over its texels, as floats.
const PYRAMID: Want = Want::new("the depth pyramid", textures::VIEW_DEPTH).samples(1);

/// The phase whose slots the file gives the pass, as `switch` sets it (on by default), or
/// none without a `pyramid` input; `samples_modified` where the pass adds to the keys it
/// reads. Errors name the slot.
pub(crate) fn take(
    switch: Option<Switch>,
    samples_modified: bool,
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
) -> Result<Option<OcclusionSlots>, PluginError> {
    if slots.kind("pyramid").is_none() {
        if switch == Some(Switch::On) || slots.kind("occluded").is_some() {
            return Err(PluginError::Invalid(
                "occlusion culling needs a \"pyramid\" input (the depth pyramid its clusters \
                 are tested against) and an \"occluded\" buffer (the clusters the first phase \
                 leaves to the second)"
                    .into(),
            ));
        }
        return Ok(None);
    }
    let phase = match samples_modified {
        true => Phase::Second,
        false => Phase::First,
    };
    let (pyramid, _) = textures::input(slots, pass, "pyramid", PYRAMID)?;
    let pyramid = pass.sampled(pyramid);
    let slot_error = |slots: &Slots<'_>, slot: &str, why: &str| PluginError::Slot {
        slot: slot.to_owned(),
        resource: slots.resource(slot).unwrap_or(slot).to_owned(),
        why: why.to_owned(),
    };
    let is_history = pass.resource(pyramid).origin.history_of().is_some();
    if phase == Phase::First && !is_history {
        return Err(slot_error(
            slots,
            "pyramid",
            "is not a history, but the first phase of occlusion culling tests clusters \
             against the previous frame's pyramid: History(of: ..) of the last depth \
             pyramid's output",
        ));
    }
    let mut modifies = false;
    let occluded = slots.write::<Buffer>("occluded", |t| {
        modifies = t.modifies;
        let role = BufferRole::Storage {
            read: t.modifies,
            write: true,
        };
        pass.buffer(t.handle, role)
    })?;
    if modifies != (phase == Phase::Second) {
        let why = match phase {
            Phase::First => "is in inputs, but the first phase writes a new list: list it in outputs only",
            Phase::Second => "is only in outputs, but the second phase reads the first's list and adds its count: list it in inputs too",
        };
        return Err(slot_error(slots, "occluded", why));
    }
    let fits = pass
        .resource(occluded)
        .buffer()
        .is_some_and(|b| b.per_sample == 0 && b.size >= LIST_HEADER + 4);
    if !fits {
        return Err(slot_error(
            slots,
            "occluded",
            "is not a buffer of a fixed size of at least 20 bytes: 16 of counts, then 4 per \
             cluster listed",
        ));
    }
    Ok(Some(OcclusionSlots {
        phase,
        pyramid,
        occluded,
        on: switch != Some(Switch::Off),
    }))
}
