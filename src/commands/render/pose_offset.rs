//! What a G-buffer's motion leaves out: the TAA presets move a deformed scene's G-buffer
//! points with their vertices through each sample's pose offset, which they store only
//! where the device's render passes hold more than WebGPU's 32 bytes per sample of colour
//! targets (docs/design/temporal-aa.md, "Deformed meshes in the G-buffer"); elsewhere a
//! skinned or morphed surface's pixels move with their mesh's transform alone, and a
//! temporal filter smears them.

use std::path::Path;

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;

use super::color_bytes;

/// The warning where `plan` (compiled from `loaded`, the file `pipeline`) moves a
/// deformed scene's G-buffer points without their pose offset: the first such pass, and
/// why where the device is the reason; `None` where it needs no offset or reads it.
pub(super) fn unposed(plan: &Plan, loaded: &LoadedGraph, pipeline: &Path) -> Option<String> {
    let pass = rgraph_passes::pose::unposed(plan, loaded)?;
    let device = color_bytes::lacking(plan, loaded, "the pose offset");
    Some(format!(
        "warning: the scene deforms meshes (skins or morph targets), but pass \"{pass}\" of \
         {} moves their G-buffer's points without the pose offset{device}: a deformed \
         surface's pixels move with its mesh's transform alone, and a temporal filter \
         smears them",
        pipeline.display()
    ))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use rgraph_core::file::load_file;
    use rgraph_core::{CompileOptions, DeviceProfile, Features};

    use super::unposed;

    /// The TAA preset for a deformed scene whose textures take the G-buffer: compiled for
    /// WebGPU's defaults it leaves the pose offset out, and says why; on a device with
    /// `color_bytes_64`, or for a scene without deformations, it says nothing.
    #[test]
    fn the_pose_offset_left_out_for_want_of_wide_targets_is_named() {
        let pipeline = Path::new("pipelines/msaa_4x_taa.ron");
        let loaded = load_file(pipeline, &crate::registry::registry()).expect("the preset loads");
        let plan_for = |profile: DeviceProfile, features: &[&str]| {
            let options = CompileOptions {
                profile,
                ..CompileOptions::default()
            };
            let features = Features::from_iter(features.iter().copied());
            loaded
                .compile_for(&options, &features)
                .expect("it compiles")
        };
        let deformed = ["untabled_textures", "deformed"];
        let plan = plan_for(DeviceProfile::webgpu(), &deformed);
        assert_eq!(
            unposed(&plan, &loaded, pipeline).as_deref(),
            Some(
                "warning: the scene deforms meshes (skins or morph targets), but pass \"motion \
                 vectors (untabled textures)\" of pipelines/msaa_4x_taa.ron moves their \
                 G-buffer's points without the pose offset (it holds the pose offset only \
                 where the device's render passes allow 64 bytes per sample of colour \
                 targets, `color_bytes_64`, which webgpu defaults does not): a deformed \
                 surface's pixels move with its mesh's transform alone, and a temporal \
                 filter smears them"
            )
        );
        let wide = DeviceProfile::webgpu().granting(&Features::from_iter(["color_bytes_64"]));
        let plan = plan_for(wide, &deformed);
        assert_eq!(unposed(&plan, &loaded, pipeline), None);
        let plan = plan_for(DeviceProfile::webgpu(), &["untabled_textures"]);
        assert_eq!(unposed(&plan, &loaded, pipeline), None);
    }
}
