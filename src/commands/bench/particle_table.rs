//! results.md's particle tables (seed 001's Tables 23-1 to 23-3), for runs that measure
//! pipelines with particle passes: per scene, each pipeline's particle and
//! image-processing pixels, GPU frame time and the time of its particle and
//! image-processing passes, the latter's saving against full-resolution particles
//! and FLIP against the reference (`--reference pipelines/particles_full_res.ron` makes
//! that full resolution); across `builtin:smoke?extent=N` scenes, the time saved at each
//! extent and the break-even extent, where the off-screen overhead outweighs the savings.

use std::fmt::Write;

use super::results::{Results, Row};

/// The file whose rows are the baseline the others save against.
const FULL: &str = "particles_full_res";
/// The scene parameter Table 23-3 varies.
const EXTENT: &str = "extent=";

fn gpu_ms(row: &Row) -> Option<f64> {
    Some(row.figures.as_ref()?.gpu_frame_ms.as_ref()?.median)
}

/// The median GPU ms of the row's particle and image-processing passes: the technique's
/// cost, without the opaque frame's (the same work in every row, but noisy on lavapipe).
fn particle_ms(row: &Row) -> Option<f64> {
    let f = row.figures.as_ref()?;
    let particles = f.particles.as_ref()?;
    f.passes
        .iter()
        .filter(|p| particles.passes.contains(&p.name))
        .map(|p| Some(p.gpu_ms.as_ref()?.median))
        .sum()
}

/// The full-resolution row of `scene`, the baseline of the others.
fn baseline<'r>(rows: &[&'r Row], scene: &str) -> Option<&'r Row> {
    rows.iter()
        .copied()
        .find(|r| r.scene == scene && r.pipeline.starts_with(FULL))
}

/// Table 23-1 for one scene's rows: nothing when none has particle figures.
pub fn per_scene(rows: &[&Row]) -> String {
    if !rows
        .iter()
        .any(|r| r.figures.as_ref().is_some_and(|f| f.particles.is_some()))
    {
        return String::new();
    }
    let mut md = String::from(
        "\n| pipeline | particle Mpx | image-processing Mpx | frame GPU ms | particle GPU ms | \
         saved vs full res | FLIP |\n|---|--:|--:|--:|--:|--:|--:|\n",
    );
    let full = rows
        .first()
        .and_then(|r| baseline(rows, &r.scene))
        .and_then(particle_ms);
    let cell = |t: Option<f64>| t.map_or("-".into(), |t| format!("{t:.2}"));
    for row in rows {
        let Some(f) = &row.figures else { continue };
        let Some(p) = &f.particles else { continue };
        let time = particle_ms(row);
        let saved = match (full, time) {
            (Some(full), Some(time)) => format!("{:+.0}%", (full - time) / full * 100.0),
            _ => "-".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {:.2} | {:.2} | {} | {} | {saved} | {} |",
            row.pipeline,
            p.particle_pixels / 1e6,
            p.image_processing_pixels / 1e6,
            cell(gpu_ms(row)),
            cell(time),
            f.image_error
                .as_ref()
                .map_or("-".into(), |e| format!("{:.4}", e.flip_mean)),
        );
    }
    md
}

/// Table 23-3 and the break-even extent, across the run's `builtin:smoke?...extent=N`
/// scenes; nothing with fewer than two.
pub fn by_extent(results: &Results) -> String {
    let rows: Vec<&Row> = results.rows.iter().collect();
    let mut extents: Vec<(u32, &str)> = rows
        .iter()
        .filter_map(|r| Some((extent(&r.scene)?, r.scene.as_str())))
        .collect();
    extents.sort();
    extents.dedup();
    if extents.len() < 2 {
        return String::new();
    }
    let mut pipelines: Vec<&str> = rows
        .iter()
        .filter(|r| extent(&r.scene).is_some() && !r.pipeline.starts_with(FULL))
        .map(|r| r.pipeline.as_str())
        .collect();
    pipelines.sort();
    pipelines.dedup();
    let mut md = String::from(
        "\n## Particles: time against the effect's size\n\n\
         | extent | particle Mpx (full res) | full res particle GPU ms |",
    );
    for p in &pipelines {
        let _ = write!(md, " {p} |");
    }
    md.push_str("\n|--:|--:|--:|");
    md.push_str(&"--:|".repeat(pipelines.len()));
    md.push('\n');
    // Per pipeline, (extent, ms saved) in extent order.
    let mut saved: Vec<Vec<(f64, f64)>> = vec![Vec::new(); pipelines.len()];
    for (e, scene) in &extents {
        let full = baseline(&rows, scene);
        let full_ms = full.and_then(particle_ms);
        let pixels = full
            .and_then(|r| r.figures.as_ref()?.particles.as_ref())
            .map_or("-".into(), |p| format!("{:.2}", p.particle_pixels / 1e6));
        let _ = write!(
            md,
            "| {e}% | {pixels} | {} |",
            full_ms.map_or("-".into(), |t| format!("{t:.2}"))
        );
        for (i, p) in pipelines.iter().enumerate() {
            let row = rows.iter().find(|r| r.scene == *scene && r.pipeline == *p);
            match (row.copied().and_then(particle_ms), full_ms) {
                (Some(t), Some(full)) => {
                    saved[i].push((f64::from(*e), full - t));
                    let _ = write!(md, " {t:.2} ({:+.2}) |", full - t);
                }
                _ => md.push_str(" - |"),
            }
        }
        md.push('\n');
    }
    md.push_str(
        "\nParticle GPU ms per technique (its particle and image-processing passes), with \
         the time it saves against full resolution in brackets. Break-even (where the off-screen overhead outweighs the savings, \
         interpolated between the extents measured):\n\n",
    );
    for (p, points) in pipelines.iter().zip(&saved) {
        let _ = writeln!(md, "- {p}: {}", break_even(points));
    }
    md
}

/// The `extent=N` of a `builtin:smoke` scene spec.
fn extent(scene: &str) -> Option<u32> {
    let query = scene.strip_prefix("builtin:smoke?")?;
    query
        .split('&')
        .find_map(|pair| pair.strip_prefix(EXTENT)?.parse().ok())
}

/// Where the savings (by extent, ascending) cross zero, interpolated linearly.
fn break_even(points: &[(f64, f64)]) -> String {
    for pair in points.windows(2) {
        let ((e0, s0), (e1, s1)) = (pair[0], pair[1]);
        if s0 <= 0.0 && s1 > 0.0 {
            let at = e0 + (e1 - e0) * (-s0) / (s1 - s0);
            return format!("an extent of about {at:.0}% (slower below, faster above)");
        }
    }
    match points.first().zip(points.last()) {
        Some(((e, s), _)) if *s > 0.0 => format!("faster at every extent measured (from {e}%)"),
        Some((_, (e, _))) => format!("slower at every extent measured (up to {e}%)"),
        None => "not measured".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::{break_even, extent};

    #[test]
    fn the_break_even_extent_is_where_the_savings_cross_zero() {
        assert_eq!(extent("builtin:smoke?count=10&extent=25"), Some(25));
        assert_eq!(extent("builtin:dense"), None);
        assert_eq!(
            break_even(&[(10.0, -2.0), (50.0, 2.0), (100.0, 5.0)]),
            "an extent of about 30% (slower below, faster above)"
        );
        assert!(break_even(&[(10.0, 1.0), (50.0, 2.0)]).starts_with("faster at every"));
        assert!(break_even(&[(10.0, -1.0), (50.0, -2.0)]).starts_with("slower at every"));
    }
}
