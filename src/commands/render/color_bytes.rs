//! The device condition under which the shipped pipelines give a G-buffer more than
//! WebGPU's 32 bytes per sample of colour targets (its material layers, a deformed
//! scene's pose offset), and the words a warning gives where a plan goes without it.

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;

/// The condition: the device's render passes allow 64 bytes per sample of colour
/// targets.
const DEVICE_CONDITION: &str = "color_bytes_64";

/// Where the file (`loaded`) declares the condition and the device `plan` was compiled
/// for lacks it, why a target it conditions on it is missing, as a clause saying what
/// the file holds only there (`holds`: "the layers"), in parentheses after a space;
/// else empty.
pub(super) fn lacking(plan: &Plan, loaded: &LoadedGraph, holds: &str) -> String {
    match loaded.graph.declared_features().contains(DEVICE_CONDITION)
        && !plan.features.iter().any(|f| f == DEVICE_CONDITION)
    {
        true => format!(
            " (it holds {holds} only where the device's render passes allow 64 bytes per \
             sample of colour targets, `{DEVICE_CONDITION}`, which {} does not)",
            plan.profile
        ),
        false => String::new(),
    }
}
