//! The "shader variants built" section of `rgraph explain --scene`: for each shader with
//! feature-gated code that a kept pass runs, the features compiled in for the scene, the
//! passes using it, and the general variant it replaces.

use rgraph_core::file::LoadedGraph;
use rgraph_core::Plan;
use rgraph_passes::variant::{plan_shader_variants, Variant};
use rgraph_scene::analysis::Features;

/// One line per variant, e.g.
/// `  light.wgsl {point_lights} instead of {directional_lights, point_lights, spot_lights}: light edges, light the rest`.
pub(super) fn text(plan: &Plan, loaded: &LoadedGraph, features: &Features) -> String {
    let variants = plan_shader_variants(features, plan, loaded);
    if variants.is_empty() {
        return "shader variants built: none (no pass runs a shader with feature-gated code)\n"
            .to_owned();
    }
    let mut text = "shader variants built:\n".to_owned();
    for used in variants {
        let variant = &used.variant;
        let replaces = match variant.is_general() {
            true => " (the general variant)".to_owned(),
            false => format!(
                " instead of {}",
                Variant::general(variant.shader).feature_list()
            ),
        };
        text += &format!("  {variant}{replaces}: {}\n", used.passes.join(", "));
    }
    text
}
