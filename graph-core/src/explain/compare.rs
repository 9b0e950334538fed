//! Two plans of one graph side by side: what a specialised plan leaves out and saves
//! against another (typically the plan for a scene that uses everything).

use std::fmt::Write;

use super::units::bytes;
use crate::plan::Plan;
use crate::resource::format_name;

/// What `plan` runs and allocates against `base` (called `base_name`, as in "the general
/// scene"): the passes that run in `base` only, each with the reason `plan` gives, the
/// resources `base` allocates and `plan` does not, the textures whose format differs
/// (with the reason `plan` gives, where a conditional format made it differ), and the
/// memory and pass counts of both.
pub fn compare(plan: &Plan, base: &Plan, base_name: &str) -> String {
    let mut out = String::new();
    let features = match base.features.is_empty() {
        true => "none".to_owned(),
        false => base.features.join(", "),
    };
    let _ = writeln!(
        out,
        "against the plan for {base_name} (features: {features}):"
    );
    let _ = writeln!(
        out,
        "  passes: {} instead of {}",
        plan.passes.len(),
        base.passes.len()
    );
    for pass in base.passes.iter().filter(|p| plan.pass(&p.name).is_none()) {
        let reason = plan
            .culled
            .iter()
            .find(|c| c.name == pass.name)
            .map_or("not in this graph", |c| c.reason.as_str());
        let _ = writeln!(out, "    - {}: {reason}", pass.name);
    }
    for resource in base.resources.iter().filter(|r| r.physical.is_some()) {
        let here = plan.find(&resource.name);
        if here.is_some_and(|r| r.physical.is_none()) {
            let reason = here.and_then(|r| r.culled.as_deref()).unwrap_or("unused");
            let _ = writeln!(
                out,
                "    not allocated: {} ({}): {reason}",
                resource.name,
                bytes(resource.bytes)
            );
        }
    }
    for (resource, shape) in plan
        .resources
        .iter()
        .filter(|r| r.physical.is_some())
        .filter_map(|r| r.texture.map(|t| (r, t)))
    {
        let Some(before) = base.find(&resource.name).and_then(|r| r.texture) else {
            continue;
        };
        if before.format == shape.format {
            continue;
        }
        let why = resource.format_because.clone().unwrap_or_else(|| {
            format!(
                "{} instead of {}",
                format_name(shape.format),
                format_name(before.format)
            )
        });
        let _ = writeln!(out, "    format of {}: {why}", resource.name);
    }
    let (now, then) = (plan.memory.physical_bytes, base.memory.physical_bytes);
    let saved = then.saturating_sub(now);
    let percent = match then {
        0 => 0.0,
        _ => 100.0 * saved as f64 / then as f64,
    };
    let _ = writeln!(
        out,
        "  memory: {} physical instead of {} ({} saved, {percent:.0}%)",
        bytes(now),
        bytes(then),
        bytes(saved)
    );
    out
}
