//! What the window's title says, and how the view picker moves: pure functions of the
//! viewer's state, so they are tested without a window.

use std::path::Path;

use rgraph_core::gpu::FrameReport;

use crate::commands::render::view::view_name;

/// `rgraph view: FILE [VIEW i/n] orbit 30 deg: pass 1.20 | pass 3.40 | GPU 4.60 ms`: the
/// file, the view shown (its position among the file's views), the camera's turn from
/// its start (`orbit`, in degrees), each pass's GPU time in milliseconds and the frame's
/// GPU total; or `frame 16.2 ms` (`frame_ms`, the time between two
/// presented frames) when no pass was timed. With `error` (the first line of a failed
/// reload), `ERROR: ...; showing the last good graph` follows the file.
pub fn title(
    pipeline: &Path,
    output: &str,
    (index, count): (usize, usize),
    orbit: f64,
    report: &FrameReport,
    frame_ms: f64,
    error: Option<&str>,
) -> String {
    let file = pipeline.file_name().map_or_else(
        || pipeline.display().to_string(),
        |f| f.to_string_lossy().into(),
    );
    let view = view_name(output).unwrap_or(output);
    // A turn back to the start sums to a tiny negative number: "0", not "-0".
    let orbit = orbit.round() + 0.0;
    let ms = |ns: u64| ns as f64 / 1e6;
    let times = match report.gpu_total_ns {
        Some(total) => {
            let mut parts: Vec<String> = report
                .passes
                .iter()
                .filter_map(|p| p.gpu_ns.map(|ns| format!("{} {:.2}", p.name, ms(ns))))
                .collect();
            parts.push(format!("GPU {:.2} ms", ms(total)));
            parts.join(" | ")
        }
        None => format!("frame {frame_ms:.1} ms (no GPU timestamps)"),
    };
    let error = match error {
        Some(e) => format!(" ERROR: {e}; showing the last good graph"),
        None => String::new(),
    };
    format!(
        "rgraph view: {file}{error} [{view} {}/{count}] orbit {orbit:.0} deg: {times}",
        index + 1
    )
}

/// The index `step` places (1 forward, -1 back) from `current` among `count` views,
/// wrapping around.
pub fn cycle(current: usize, count: usize, step: isize) -> usize {
    match count {
        0 => 0,
        n => (current as isize + step).rem_euclid(n as isize) as usize,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rgraph_core::gpu::PassTiming;
    use rgraph_core::PassKind;

    fn report(timed: bool) -> FrameReport {
        let pass = |name: &str, ns: u64| PassTiming {
            name: name.into(),
            kind: PassKind::Render,
            gpu_ns: timed.then_some(ns),
            cpu_ns: 1,
            held_bytes: 0,
        };
        FrameReport {
            passes: vec![pass("gbuffer", 1_200_000), pass("light", 3_400_000)],
            gpu_total_ns: timed.then_some(4_600_000),
            textures_allocated: 0,
            buffers_allocated: 0,
            record_submit_ns: 1,
        }
    }

    #[test]
    fn titles_name_the_view_and_the_pass_times() {
        let path = Path::new("pipelines/a.ron");
        assert_eq!(
            title(
                path,
                "debug.edges",
                (1, 3),
                -30.0,
                &report(true),
                20.0,
                None
            ),
            "rgraph view: a.ron [edges 2/3] orbit -30 deg: gbuffer 1.20 | light 3.40 | GPU 4.60 ms"
        );
        assert_eq!(
            title(path, "color", (0, 1), -1e-12, &report(false), 16.25, None),
            "rgraph view: a.ron [final 1/1] orbit 0 deg: frame 16.2 ms (no GPU timestamps)"
        );
    }

    #[test]
    fn a_failed_reload_is_in_the_title() {
        let error = "a.ron:3:5: error: unknown plugin \"nope\"";
        let shown = title(
            Path::new("a.ron"),
            "color",
            (0, 1),
            0.0,
            &report(true),
            1.0,
            Some(error),
        );
        assert!(
            shown.starts_with(&format!(
                "rgraph view: a.ron ERROR: {error}; showing the last good graph [final 1/1]"
            )),
            "{shown}"
        );
    }

    #[test]
    fn the_picker_wraps_around() {
        assert_eq!(cycle(0, 3, 1), 1);
        assert_eq!(cycle(2, 3, 1), 0);
        assert_eq!(cycle(0, 3, -1), 2);
        assert_eq!(cycle(0, 0, 1), 0);
    }
}
