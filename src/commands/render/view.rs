//! Views and graph outputs: `final` is the pipeline's "color" output, any other view NAME
//! its "debug.NAME" output (the contract every deferred pipeline keeps).

use super::error::RenderError;
use crate::frame::FrameError;

pub(super) const FINAL: &str = "final";
const FINAL_OUTPUT: &str = "color";
const DEBUG_PREFIX: &str = "debug.";

/// The output a view reads.
pub fn output_name(view: &str) -> String {
    if view == FINAL {
        FINAL_OUTPUT.to_string()
    } else {
        format!("{DEBUG_PREFIX}{view}")
    }
}

/// The view an output shows: `final` for "color", NAME for "debug.NAME", `None` for
/// any other output.
pub fn view_name(output: &str) -> Option<&str> {
    match output {
        FINAL_OUTPUT => Some(FINAL),
        o => o.strip_prefix(DEBUG_PREFIX),
    }
}

/// The outputs among `outputs` that are views, "color" first, then the debug views by
/// name: the order a viewer cycles through them.
pub fn viewable<'a>(outputs: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut views: Vec<&str> = outputs.filter(|o| view_name(o).is_some()).collect();
    views.sort_by_key(|o| (*o != FINAL_OUTPUT, *o));
    views
}

/// A view the pipeline lacks becomes an error listing the views it has; other errors
/// pass through.
pub fn unknown(error: FrameError, view: &str) -> RenderError {
    match error {
        FrameError::NotAnOutput { pipeline, source } => RenderError::UnknownView {
            view: view.to_string(),
            pipeline,
            output: source.name,
            offered: offered(source.outputs.iter().map(String::as_str)),
        },
        other => RenderError::Frame(other),
    }
}

/// The views among a pipeline's outputs, `final` first.
fn offered<'a>(outputs: impl Iterator<Item = &'a str>) -> String {
    let views: Vec<&str> = viewable(outputs)
        .into_iter()
        .filter_map(view_name)
        .collect();
    if views.is_empty() {
        "none (it exports neither \"color\" nor \"debug.NAME\")".into()
    } else {
        views.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::{offered, output_name, viewable};

    #[test]
    fn views_name_outputs() {
        assert_eq!(output_name("final"), "color");
        assert_eq!(output_name("edges"), "debug.edges");
    }

    #[test]
    fn offered_views_put_final_first_and_skip_other_outputs() {
        let outputs = ["debug.normals", "color", "history", "debug.edges"];
        assert_eq!(offered(outputs.into_iter()), "final, edges, normals");
        assert!(offered(["history"].into_iter()).starts_with("none"));
    }

    #[test]
    fn viewable_outputs_put_color_first() {
        let outputs = ["debug.normals", "history", "color", "debug.edges"];
        assert_eq!(
            viewable(outputs.into_iter()),
            ["color", "debug.edges", "debug.normals"]
        );
    }
}
