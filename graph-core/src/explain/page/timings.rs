//! Per-pass times on the page: a strip whose segments are the passes' shares of the GPU
//! frame, and a row of bars under each pass for GPU and CPU time.

use maud::{html, Markup};
use serde::Serialize;

use super::hues::pass_hue;
use crate::plan::Plan;

/// What a measurement said of a plan's passes (a bench's medians), matched to the plan's
/// passes by name: a pass without a time shows as not timed, a timed pass the plan lacks
/// is named under the bars.
#[derive(Clone, Debug, Serialize)]
pub struct Timings {
    /// Where the times come from, as the page says it: the results file, row, size and
    /// adapter.
    pub source: String,
    /// GPU time of the whole frame, in milliseconds; `None` without timestamps.
    pub gpu_frame_ms: Option<f64>,
    /// CPU time to record every pass.
    pub cpu_record_ms: Option<f64>,
    /// Per-pass times, matched to the plan's passes by name.
    pub passes: Vec<PassTime>,
}

/// One pass's measured times.
#[derive(Clone, Debug, Serialize)]
pub struct PassTime {
    /// The pass's name.
    pub name: String,
    /// GPU time in milliseconds; `None` where the device has no timestamps.
    pub gpu_ms: Option<f64>,
    /// CPU time to record it, in milliseconds, where measured.
    pub cpu_ms: Option<f64>,
}

/// Which of a pass's times a row shows.
#[derive(Copy, Clone)]
pub(super) enum Clock {
    Gpu,
    Cpu,
}

impl Clock {
    fn of(self, time: &PassTime) -> Option<f64> {
        match self {
            Clock::Gpu => time.gpu_ms,
            Clock::Cpu => time.cpu_ms,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Clock::Gpu => "GPU",
            Clock::Cpu => "CPU",
        }
    }
}

impl Timings {
    /// The time of the pass called `name`.
    pub fn pass(&self, name: &str) -> Option<&PassTime> {
        self.passes.iter().find(|p| p.name == name)
    }

    /// One line for a pass's tooltip: its GPU and CPU time, or that it was not timed.
    pub(super) fn describe(&self, name: &str) -> String {
        match self.pass(name) {
            Some(t) => format!(
                "GPU {}, CPU {} (medians)",
                t.gpu_ms
                    .map_or("not measured".into(), |v| format!("{} ms", ms(v))),
                t.cpu_ms
                    .map_or("not measured".into(), |v| format!("{} ms", ms(v)))
            ),
            None => "not timed: the measured plan has no pass of this name".into(),
        }
    }

    /// A table row of `clock`'s bars, one cell per pass of `plan`, each bar's height its
    /// share of the slowest pass.
    pub(super) fn row(&self, plan: &Plan, clock: Clock) -> Markup {
        let max = plan
            .passes
            .iter()
            .filter_map(|p| self.pass(&p.name).and_then(|t| clock.of(t)))
            .fold(0.0_f64, f64::max);
        let class = match clock {
            Clock::Gpu => "tbar gpu",
            Clock::Cpu => "tbar cpu",
        };
        html! {
            tr.time {
                th scope="row" { (clock.name()) " ms" span.meta { "median" } }
                @for pass in &plan.passes {
                    @let time = self.pass(&pass.name).and_then(|t| clock.of(t));
                    td {
                        @match time {
                            Some(v) => {
                                @let share = if max > 0.0 { v / max } else { 0.0 };
                                div.tcell {
                                    div class=(class) style=(format!("--v:{share:.3}")) {}
                                    span.val { (ms(v)) }
                                }
                            }
                            None => {
                                div.tcell { span.val.none { "–" } span.sr-only { "not timed" } }
                            }
                        }
                    }
                }
            }
        }
    }

    /// The GPU frame as a strip of the passes' shares, widest first where the time goes;
    /// with the timed passes this plan does not run named beneath.
    pub(super) fn strip(&self, plan: &Plan) -> Markup {
        let timed: Vec<(usize, &str, f64)> = plan
            .passes
            .iter()
            .enumerate()
            .filter_map(|(i, p)| Some((i, p.name.as_str(), self.pass(&p.name)?.gpu_ms?)))
            .filter(|(_, _, v)| *v > 0.0)
            .collect();
        let total: f64 = timed.iter().map(|(_, _, v)| v).sum();
        let label = timed
            .iter()
            .map(|(_, name, v)| format!("{name} {} ms ({:.0}%)", ms(*v), 100.0 * v / total))
            .collect::<Vec<_>>()
            .join(", ");
        let elsewhere: Vec<&str> = self
            .passes
            .iter()
            .filter(|t| plan.pass(&t.name).is_none())
            .map(|t| t.name.as_str())
            .collect();
        html! {
            @if !timed.is_empty() {
                figure.strip-wrap {
                    figcaption { "Where the GPU time goes: each pass's share of " (ms(total)) " ms" }
                    div.strip role="img" aria-label=(format!("GPU time by pass: {label}")) {
                        @for (i, name, v) in &timed {
                            span.seg style=(format!("flex-grow:{v:.4};--h:{}", pass_hue(*i))) title=(format!("{name}: {} ms", ms(*v))) {
                                (name)
                            }
                        }
                    }
                }
            }
            @if !elsewhere.is_empty() {
                p.note { "Timed passes this plan does not run: " (elsewhere.join(", ")) }
            }
        }
    }
}

/// Milliseconds with three significant digits or so.
pub(super) fn ms(v: f64) -> String {
    match v.abs() {
        a if a >= 100.0 => format!("{v:.0}"),
        a if a >= 10.0 => format!("{v:.1}"),
        a if a >= 1.0 => format!("{v:.2}"),
        _ => format!("{v:.3}"),
    }
}
