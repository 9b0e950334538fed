//! Views and graph outputs: `final` is the pipeline's "color" output, any other view NAME
//! its "debug.NAME" output (the contract every deferred pipeline keeps).

use std::path::Path;

use graph_core::file::LoadedGraph;

use super::error::RenderError;

const FINAL: &str = "final";
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

/// Keeps only `view`'s output exported, so compiling culls the passes only the other
/// views need. An output the pipeline lacks is an error listing the views it has.
pub fn select(loaded: &mut LoadedGraph, view: &str, pipeline: &Path) -> Result<(), RenderError> {
    let output = output_name(view);
    loaded
        .keep_outputs(&[output.as_str()])
        .map_err(|e| RenderError::UnknownView {
            view: view.to_string(),
            pipeline: pipeline.to_path_buf(),
            output: output.clone(),
            offered: offered(e.outputs.iter().map(String::as_str)),
        })
}

/// The views among a pipeline's outputs, `final` first.
fn offered<'a>(outputs: impl Iterator<Item = &'a str>) -> String {
    let mut views: Vec<&str> = outputs
        .filter_map(|o| match o {
            FINAL_OUTPUT => Some(FINAL),
            o => o.strip_prefix(DEBUG_PREFIX),
        })
        .collect();
    views.sort_by_key(|v| (*v != FINAL, *v));
    if views.is_empty() {
        "none (it exports neither \"color\" nor \"debug.NAME\")".into()
    } else {
        views.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::{offered, output_name};

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
}
