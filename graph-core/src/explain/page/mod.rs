//! The plan as one self-contained HTML page for a reviewer: the passes in execution order
//! as a timeline, each resource's lifetime as a bar coloured by the physical texture or
//! buffer it occupies (one colour on several rows is memory they share), bytes and
//! totals, what was culled or dropped and why, what the plan was specialised for, per-pass
//! times when a bench measured them, and what differs from another plan when one is given.
//!
//! The page is rendered here, in Rust, from the [`Plan`] that `--format json` serializes,
//! rather than by a script from that JSON: it reads without JavaScript, tests check its
//! structure without a browser, and every string from a graph file (pass and resource
//! names, the reasons that quote conditions) enters it only through maud's escaping. The
//! page's data, the plan as `--format json` writes it with the setting, timings and
//! compared plan, is embedded beside it for tools ([`DATA_ID`]). Its one script pins
//! tooltips open on click; a Content-Security-Policy allows that script (by its hash) and
//! inline styles and nothing else, so the page cannot reach the network.

mod diff;
mod hues;
mod not_run;
mod timeline;
mod timings;

pub use timings::{PassTime, Timings};

use base64::Engine;
use maud::{html, Markup, PreEscaped, DOCTYPE};
use serde::Serialize;
use sha2::{Digest, Sha256};

use super::units::{bytes, counted};
use crate::plan::Plan;
use diff::Diff;
use timeline::allocations;

/// The element whose text is the page's data as JSON (`<script type="application/json">`).
pub const DATA_ID: &str = "page-data";

const STYLE: &str = include_str!("style.css");
const SCRIPT: &str = include_str!("page.js");

/// What a page shows: a plan and what it was compiled for, and optionally its times and
/// another plan to compare it with. Serialized into the page as its data.
#[derive(Serialize)]
pub struct Page<'a> {
    /// What the plan is of, as the user named it: the graph file's path.
    pub title: String,
    /// The plan drawn.
    pub plan: &'a Plan,
    /// The scene and parameters it was compiled for.
    pub setting: Setting,
    /// Measured times of its passes, drawn as bars.
    pub timings: Option<Timings>,
    /// A plan to highlight the differences from.
    pub compare: Option<Against<'a>>,
}

/// What the plan was specialised for, as a person reads it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Setting {
    /// The scene the plan was compiled for, as given (`builtin:spheres`, a glTF path);
    /// `None` for the plan of no scene.
    pub scene: Option<String>,
    /// The scene's features as its analysis found them (the plan's own
    /// [`features`](Plan::features) are those of them the graph declares).
    pub scene_features: Vec<String>,
    /// Every parameter the graph file declares, with the value it was compiled with.
    pub parameters: Vec<Parameter>,
}

/// A graph-file parameter and the value a plan was compiled with.
#[derive(Clone, Debug, Serialize)]
pub struct Parameter {
    /// The parameter's name in the graph file.
    pub name: String,
    /// The value the plan was compiled with.
    pub value: u32,
    /// Given by the user rather than the file's default.
    pub given: bool,
}

/// Another plan of the same graph (another scene's) or of another graph (the file before
/// a change), which the page highlights the differences from.
#[derive(Serialize)]
pub struct Against<'a> {
    /// What the other plan is, as the page names it: "pipelines/old.ron",
    /// "the plan for builtin:unlit".
    pub label: String,
    /// The other plan.
    pub plan: &'a Plan,
}

/// The page as one HTML document with its style, script and data inline.
pub fn html(page: &Page) -> String {
    let plan = page.plan;
    let diff = page
        .compare
        .as_ref()
        .map(|against| Diff::of(plan, against.plan, &against.label));
    let script_hash = Sha256::digest(SCRIPT.as_bytes());
    let policy = format!(
        "default-src 'none'; style-src 'unsafe-inline'; img-src data:; script-src 'sha256-{}'",
        base64::engine::general_purpose::STANDARD.encode(script_hash)
    );
    let document = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                meta http-equiv="Content-Security-Policy" content=(policy);
                meta name="viewport" content="width=device-width, initial-scale=1";
                meta name="color-scheme" content="light dark";
                title { "Plan of " (page.title) " (rgraph)" }
                style { (PreEscaped(STYLE)) }
            }
            body {
                header {
                    h1 { "Plan of " code { (page.title) } }
                    (summary(page))
                }
                main {
                    (setting(page))
                    @if let Some(diff) = &diff { (diff.summary(plan, page.compare.as_ref().map(|c| c.plan))) }
                    section aria-labelledby="timeline-h" {
                        h2 #timeline-h { "Passes and resource lifetimes" }
                        (timeline::legend(plan, page.timings.is_some(), diff.is_some()))
                        (not_run::list(plan, diff.as_ref()))
                        @if let Some(timings) = &page.timings { (timings.strip(plan)) }
                        (timeline::table(plan, page.timings.as_ref(), diff.as_ref()))
                    }
                }
                script type="application/json" id=(DATA_ID) { (PreEscaped(data(page))) }
                script { (PreEscaped(SCRIPT)) }
            }
        }
    };
    document.into_string()
}

/// The page's data as JSON that cannot end its `<script>` element: every `<` (which JSON
/// only has inside strings) written as `\u003c`, so no `</script>` or `<!--` in a name
/// reaches the HTML parser.
fn data(page: &Page) -> String {
    // Plain data of strings and numbers: serializing it cannot fail.
    let json = serde_json::to_string(page).expect("a page's data serializes");
    json.replace('<', "\\u003c")
}

/// The first lines: size, profile, counts and memory.
fn summary(page: &Page) -> Markup {
    let plan = page.plan;
    let (w, h) = plan.output_size;
    let m = &plan.memory;
    let saved = m.logical_bytes.saturating_sub(m.physical_bytes);
    let percent = match m.logical_bytes {
        0 => 0.0,
        logical => 100.0 * saved as f64 / logical as f64,
    };
    html! {
        p.sub {
            (w) "×" (h) " for " (plan.profile) " · "
            (counted(plan.passes.len(), "pass", "passes")) " run, " (plan.culled.len()) " not run · "
            (counted(plan.resources.len(), "resource", "resources")) " in "
            (allocations(plan))
        }
        dl.totals {
            div { dt { "Logical memory" } dd #logical-bytes { (bytes(m.logical_bytes)) } }
            div { dt { "Physical memory" } dd #physical-bytes { (bytes(m.physical_bytes)) } }
            div { dt { "Saved by sharing" } dd { (bytes(saved)) " (" (format!("{percent:.0}")) "%)" } }
            @if let Some(frame) = page.timings.as_ref().and_then(|t| t.gpu_frame_ms) {
                div { dt { "GPU frame" } dd { (timings::ms(frame)) " ms" } }
            }
        }
    }
}

/// The scene, features and parameters the plan was compiled for, and where the times and
/// the compared plan come from.
fn setting(page: &Page) -> Markup {
    let s = &page.setting;
    let list = |items: &[String]| match items.is_empty() {
        true => "none".to_owned(),
        false => items.join(", "),
    };
    html! {
        section aria-labelledby="setting-h" {
            h2 #setting-h { "Specialised for" }
            dl.setting {
                dt { "Scene" }
                dd {
                    @match &s.scene {
                        Some(scene) => code { (scene) },
                        None => "none given: the plan for no scene features",
                    }
                }
                @if s.scene.is_some() {
                    dt { "Scene features" }
                    dd { (list(&s.scene_features)) }
                }
                dt { "Features the plan was compiled for" }
                dd { (list(&page.plan.features)) }
                dt { "Parameters" }
                dd {
                    @if s.parameters.is_empty() { "none declared" }
                    @for (i, p) in s.parameters.iter().enumerate() {
                        @if i > 0 { ", " }
                        code { (p.name) " = " (p.value) }
                        @if p.given { " (given)" } @else { " (the file's default)" }
                    }
                }
                @if let Some(timings) = &page.timings {
                    dt { "Times" }
                    dd { (timings.source) }
                }
                @if let Some(against) = &page.compare {
                    dt { "Compared with" }
                    dd { (against.label) }
                }
            }
        }
    }
}
