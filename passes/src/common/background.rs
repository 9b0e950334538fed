//! A scene pass's color targets filled where its meshes draw nothing, after them, instead
//! of cleared before them: a full-screen draw at the far depth, tested for equality
//! against the depth the pass cleared, writes each target's clear value to exactly the
//! samples no mesh covered, so the targets end as a clear and the meshes would leave
//! them, bit for bit. A multisampled clear goes through the ROPs, which on the H200 cost
//! as much as a full-screen pass (builtin:dense at 3840x2160 4x: 7.1 of the lean
//! G-buffer pass's 20.2 ms, 14.2 of the five-target one's 33.9, 4.7 of forward's 20.1:
//! docs/design/compute-raster.md, run visibility-merged); the fill writes the background's
//! samples only and depth-culls the rest.

use rgraph_core::file::{PluginError, Slots};
use rgraph_core::{PassBuilder, TextureHandle};

use super::textures::{self, Want};

/// A scene pass's color targets as it declares them, each begun for the fill (overwritten)
/// unless the pass draws over a target it reads: then every fresh one is cleared to its
/// value instead, and nothing is filled.
pub(crate) struct FilledTargets {
    fill: bool,
    handles: Vec<TextureHandle>,
    values: Vec<(&'static str, [f64; 4])>,
}

impl FilledTargets {
    /// For a pass that may write the slots `named`.
    pub fn new(slots: &Slots<'_>, named: &[&str]) -> FilledTargets {
        FilledTargets {
            fill: !named.iter().any(|slot| slots.modifies(slot)),
            handles: Vec::with_capacity(named.len()),
            values: Vec::with_capacity(named.len()),
        }
    }

    /// Declares `slot` as the next color attachment: of WGSL type `ty` in the fill's
    /// output, holding `clear` where no mesh draws. Returns its handle.
    pub fn push(
        &mut self,
        slots: &mut Slots<'_>,
        pass: &mut PassBuilder<'_>,
        slot: &str,
        want: Want,
        (ty, clear): (&'static str, [f64; 4]),
    ) -> Result<TextureHandle, PluginError> {
        let (target, _) = match self.fill {
            true => textures::covered_output(slots, pass, slot, want)?,
            false => textures::color_output(slots, pass, slot, want, clear)?,
        };
        self.handles.push(target);
        self.values.push((ty, clear));
        Ok(target)
    }

    /// The attachments declared, in location order.
    pub fn handles(&self) -> &[TextureHandle] {
        &self.handles
    }

    /// Only the attachments `kept` marks (one flag per attachment, in order): those a
    /// frame's plan keeps of a pass whose writes may be dropped, at consecutive locations.
    pub fn only(&self, kept: &[bool]) -> FilledTargets {
        let keep = |i: &usize| kept.get(*i).copied().unwrap_or(true);
        FilledTargets {
            fill: self.fill,
            handles: (0..self.handles.len())
                .filter(keep)
                .map(|i| self.handles[i])
                .collect(),
            values: (0..self.values.len())
                .filter(keep)
                .map(|i| self.values[i])
                .collect(),
        }
    }

    /// Whether the pass fills its targets (`SceneDraw::fill_background`).
    pub fn fill(&self) -> bool {
        self.fill
    }

    /// The fill's WGSL ([`fill_wgsl`]), or nothing where the targets are cleared.
    pub fn wgsl(&self) -> String {
        match self.fill {
            true => fill_wgsl(&self.values),
            false => String::new(),
        }
    }

    /// The attachments, in location order.
    pub fn into_handles(self) -> Vec<TextureHandle> {
        self.handles
    }
}

/// The WGSL of the fill's fragment stage, `fs_background`, for targets of these WGSL
/// types (`vec4<f32>`, `vec2<u32>`, ...) holding these clear values, at locations 0 on:
/// generated, since the values are the pass's parameters. Integer targets take their
/// values' integer parts, as a clear does.
pub(crate) fn fill_wgsl(targets: &[(&str, [f64; 4])]) -> String {
    let fields: String = targets
        .iter()
        .enumerate()
        .map(|(location, (ty, _))| format!("    @location({location}) t{location}: {ty},\n"))
        .collect();
    let values: Vec<String> = targets.iter().map(|(ty, v)| literal(ty, v)).collect();
    format!(
        "// Generated: each target's value where no mesh draws (common/background.rs).\n\
         struct BackgroundOut {{\n{fields}}}\n\n\
         @fragment\nfn fs_background() -> BackgroundOut {{\n    return BackgroundOut({});\n}}\n",
        values.join(", ")
    )
}

/// `value` as a WGSL constructor of `ty`: as many components as the type has.
fn literal(ty: &str, value: &[f64; 4]) -> String {
    let count = match ty.get(3..4) {
        Some(n) => n.parse().unwrap_or(1),
        None => 1,
    };
    let integer = ty.contains("u32") || ty.contains("i32");
    let components: Vec<String> = value[..count]
        .iter()
        .map(|&c| match integer {
            true => format!("{}", c.trunc() as i64),
            false => format!("{c:?}"),
        })
        .collect();
    format!("{ty}({})", components.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fill_returns_each_targets_clear_value_in_its_type() {
        let wgsl = fill_wgsl(&[
            ("vec4<f32>", [0.25, 0.0, 1.0, 1.0]),
            ("vec2<u32>", [513.0, 7.0, 0.0, 0.0]),
        ]);
        assert!(wgsl.contains("@location(0) t0: vec4<f32>,"), "{wgsl}");
        assert!(wgsl.contains("@location(1) t1: vec2<u32>,"), "{wgsl}");
        assert!(
            wgsl.contains(
                "return BackgroundOut(vec4<f32>(0.25, 0.0, 1.0, 1.0), vec2<u32>(513, 7));"
            ),
            "{wgsl}"
        );
    }
}
