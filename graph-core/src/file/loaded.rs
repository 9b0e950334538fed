//! A graph loaded from a file: the graph itself, its names, and where everything was
//! written, so compiling it reports errors at file positions.

use std::collections::BTreeMap;

use super::any_handle::AnyHandle;
use super::error::FileErrors;
use super::params::GraphParams;
use super::spans::Spans;
use crate::compile::CompileOptions;
use crate::condition::Features;
use crate::graph::Graph;
use crate::handle::{BufferHandle, TextureHandle};
use crate::plan::Plan;

/// A graph file, declared: compile it (as often as needed, for any output size or
/// profile) with [`LoadedGraph::compile`], and bind it to its plans with
/// [`CompiledGraph`](crate::CompiledGraph) to execute them.
pub struct LoadedGraph {
    /// The declared graph, with the plugins' record callbacks; compile and execute it
    /// through the `LoadedGraph` to get errors positioned in the file.
    pub graph: Graph,
    /// The handle each name in the file denotes.
    pub names: Names,
    /// The plugin each declared pass names, by pass name.
    pub(crate) plugins: BTreeMap<String, String>,
    /// Each declared pass's slots, by pass name: the version each names.
    pub(crate) slots: BTreeMap<String, BTreeMap<String, AnyHandle>>,
    /// Every parameter the file declares, with the value it was loaded with.
    pub(crate) params: GraphParams,
    pub(crate) spans: Spans,
}

impl LoadedGraph {
    /// [`Graph::compile`], with each error placed in the file: at the slot where the
    /// pass names the resource, at the pass, or at the resource's declaration.
    pub fn compile(&self, options: &CompileOptions) -> Result<Plan, FileErrors> {
        self.compile_for(options, &Features::new())
    }

    /// Checks the graph for `options` (its device profile and output size) as `rgraph
    /// validate` does, returning the plan for no features. A file with conditions is
    /// compiled for each of its [witnesses](crate::Graph::witnesses) too, so that every
    /// pass and resource is checked in some graph, even one only a feature off by default
    /// keeps; their errors are reported together. A witness naming
    /// [device conditions](crate::DEVICE_CONDITIONS) is compiled for the profile with those
    /// features added, so a branch for 64-bit atomics is checked on any profile.
    pub fn validate(&self, options: &CompileOptions) -> Result<Plan, FileErrors> {
        let errors: Vec<_> = self
            .graph
            .witnesses()
            .iter()
            .skip(1)
            .filter_map(|features| {
                let options = CompileOptions {
                    output_size: options.output_size,
                    profile: options.profile.granting(features),
                };
                self.compile_for(&options, features).err()
            })
            .flat_map(|e| e.0)
            .collect();
        // Sorting drops the errors several feature sets found alike.
        match (self.compile(options), errors.is_empty()) {
            (Ok(plan), true) => Ok(plan),
            (Ok(_), false) => Err(FileErrors::sorted(errors)),
            (Err(e), _) => Err(FileErrors::sorted(errors.into_iter().chain(e.0).collect())),
        }
    }

    /// [`Graph::compile_for`], with errors placed as by [`compile`](Self::compile).
    pub fn compile_for(
        &self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Plan, FileErrors> {
        self.graph.compile_for(options, features).map_err(|errors| {
            FileErrors::sorted(errors.0.into_iter().map(|e| self.spans.locate(e)).collect())
        })
    }

    /// Every parameter the file declares, with the value it was loaded with (given, or the
    /// default).
    pub fn params(&self) -> &GraphParams {
        &self.params
    }

    /// The plugin the file names for the pass called `pass` (a plan's passes carry
    /// their names): what tools that know the plugins say about a plan's passes.
    pub fn plugin(&self, pass: &str) -> Option<&str> {
        self.plugins.get(pass).map(String::as_str)
    }

    /// The version the slot `slot` of the pass called `pass` names: the one it writes for
    /// an output, else the one it reads; `None` where the file gives the pass no such
    /// slot. With [`plugin`](Self::plugin), what tools that know a plugin's slots say
    /// about a plan's pass (which of its optional accesses the plan keeps, say).
    pub fn slot(&self, pass: &str, slot: &str) -> Option<AnyHandle> {
        self.slots.get(pass)?.get(slot).copied()
    }

    /// The file's outputs, sorted: for each exported resource, the name of the version it
    /// keeps (its final one).
    pub fn outputs(&self) -> Vec<&str> {
        self.names
            .iter()
            .filter(|(_, handle)| {
                let resource = &self.graph.resources[handle.id().index()];
                resource.exported && handle.version() + 1 == resource.versions
            })
            .map(|(name, _)| name)
            .collect()
    }

    /// Keeps only the outputs named in `keep` exported, so that compiling culls the passes
    /// only the other outputs need (a tool showing one of several debug views runs just
    /// that view's passes). Changes nothing when a name is not an output.
    pub fn keep_outputs(&mut self, keep: &[&str]) -> Result<(), NotAnOutput> {
        let outputs = self.outputs();
        if let Some(missing) = keep.iter().find(|name| !outputs.contains(name)) {
            return Err(NotAnOutput {
                name: missing.to_string(),
                outputs: outputs.iter().map(|o| o.to_string()).collect(),
            });
        }
        let kept: Vec<usize> = keep
            .iter()
            .filter_map(|name| self.names.get(name))
            .map(|handle| handle.id().index())
            .collect();
        for (index, resource) in self.graph.resources.iter_mut().enumerate() {
            resource.exported &= kept.contains(&index);
        }
        Ok(())
    }
}

impl crate::plan_cache::sealed::Graphs for LoadedGraph {
    #[cfg(feature = "gpu")]
    fn graph_mut(&mut self) -> &mut Graph {
        &mut self.graph
    }
}

impl crate::plan_cache::Compile for LoadedGraph {
    type Error = FileErrors;

    fn compile_for(
        &self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Plan, FileErrors> {
        LoadedGraph::compile_for(self, options, features)
    }

    fn relevant(&self, features: &Features) -> Features {
        self.graph.relevant(features)
    }
}

/// [`LoadedGraph::keep_outputs`] was asked to keep a name that is not an output.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("\"{name}\" is not an output of the graph (outputs: {})", outputs.join(", "))]
pub struct NotAnOutput {
    /// The name asked for.
    pub name: String,
    /// The graph's outputs, sorted.
    pub outputs: Vec<String>,
}

/// Names in a graph file and the handles they denote: declared resources (the version
/// their writer produces, or version 0 of an import nobody writes) and version names.
#[derive(Clone, Debug, Default)]
pub struct Names(pub(crate) BTreeMap<String, AnyHandle>);

impl Names {
    /// The handle `name` denotes, of either kind.
    pub fn get(&self, name: &str) -> Option<AnyHandle> {
        self.0.get(name).copied()
    }

    /// The texture `name` denotes; `None` for an unknown name or a buffer.
    pub fn texture(&self, name: &str) -> Option<TextureHandle> {
        self.get(name).and_then(|h| h.typed())
    }

    /// The buffer `name` denotes; `None` for an unknown name or a texture.
    pub fn buffer(&self, name: &str) -> Option<BufferHandle> {
        self.get(name).and_then(|h| h.typed())
    }

    /// Every name, sorted.
    pub fn iter(&self) -> impl Iterator<Item = (&str, AnyHandle)> {
        self.0.iter().map(|(n, h)| (n.as_str(), *h))
    }
}

#[cfg(test)]
mod tests {
    use super::NotAnOutput;
    use crate::compile::CompileOptions;
    use crate::file::{load_str, LoadedGraph, Registry};

    /// Two outputs, each cleared by its own pass.
    fn two_outputs() -> LoadedGraph {
        let text = r#"Graph(
            resources: {
                "a": Texture(format: "rgba8unorm"),
                "b": Texture(format: "rgba8unorm"),
            },
            passes: [
                (name: "clear_a", plugin: "clear", outputs: { "target": "a" }),
                (name: "clear_b", plugin: "clear", outputs: { "target": "b" }),
            ],
            outputs: ["a", "b"],
        )"#;
        load_str("two.ron", text, &Registry::with_builtins()).expect("the graph loads")
    }

    #[test]
    fn keeping_one_output_culls_the_passes_of_the_others() {
        let mut loaded = two_outputs();
        assert_eq!(loaded.outputs(), ["a", "b"]);
        loaded.keep_outputs(&["b"]).unwrap();
        assert_eq!(loaded.outputs(), ["b"]);
        let plan = loaded.compile(&CompileOptions::default()).unwrap();
        let passes: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(passes, ["clear_b"]);
        assert_eq!(plan.culled[0].name, "clear_a");
    }

    #[test]
    fn keeping_a_name_that_is_not_an_output_changes_nothing() {
        let mut loaded = two_outputs();
        let error = loaded.keep_outputs(&["b", "c"]).unwrap_err();
        assert_eq!(
            error,
            NotAnOutput {
                name: "c".into(),
                outputs: vec!["a".into(), "b".into()],
            }
        );
        assert_eq!(
            error.to_string(),
            "\"c\" is not an output of the graph (outputs: a, b)"
        );
        assert_eq!(loaded.outputs(), ["a", "b"]);
    }

    #[test]
    fn each_pass_knows_its_plugin() {
        let loaded = two_outputs();
        assert_eq!(loaded.plugin("clear_a"), Some("clear"));
        assert_eq!(loaded.plugin("present"), None);
    }
}
