//! A pipeline file loaded for one scene, keeping only the outputs a command reads, and
//! compiled for that scene's features.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rgraph_core::file::{
    load_file_with, load_str_with, ErrorKind, FileErrors, GraphParams, LoadedGraph, Registry,
};
use rgraph_passes::variant::Variants;
use rgraph_passes::{Background, Host, Overrides};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::Scene;

use super::FrameError;
use crate::registry::registry_for;

/// What the deferred plugins draw: `scene` with `overrides`.
pub fn host(scene: Arc<Scene>, overrides: Overrides) -> Arc<Host> {
    Arc::new(Host::new(scene, overrides))
}

/// A loaded graph file whose exports are exactly the outputs asked for, so compiling it
/// culls the passes only the other outputs need, and the features it compiles for: its
/// scene's, so the file's conditions drop what the scene does not use.
pub struct Pipeline {
    pub path: PathBuf,
    pub loaded: LoadedGraph,
    /// The outputs kept, in the order asked for.
    pub outputs: Vec<String>,
    /// Every output the file declares, sorted.
    pub offered: Vec<String>,
    /// What it is compiled for: [`Session::prepare`](super::Session::prepare) compiles
    /// the file for these features' names.
    pub features: SceneFeatures,
    /// What the deferred plugins build their shader variants for: `features`, except
    /// for [`Specialise::PlanOnly`].
    pub shader_features: SceneFeatures,
    /// The scene the plugins draw, whose textures
    /// [`Session::prepare`](super::Session::prepare) checks against the device.
    pub scene: Arc<Scene>,
    /// The background the host asked for, which
    /// [`Session::prepare`](super::Session::prepare) checks a pass draws.
    pub background: Option<Background>,
}

/// What a pipeline is compiled for.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Specialise {
    /// The scene's features: the file's conditions drop what the scene does not use,
    /// and the shaders are the scene's variants.
    ToScene,
    /// The scene's plan with the general shaders: it tells what the shader variants
    /// save apart from what the plan's changes (passes, formats) save.
    PlanOnly,
    /// A scene using every feature, with the general shaders: the file's general
    /// pipeline, which measures what specialising saves (and shows a view the scene's
    /// plan drops).
    General,
}

impl Specialise {
    fn variants(self) -> Variants {
        match self {
            Specialise::ToScene => Variants::Scene,
            Specialise::PlanOnly | Specialise::General => Variants::General,
        }
    }

    /// The features the file is compiled for, and those its shaders are built for
    /// (what [`Self::variants`] makes of the scene), analysing the scene at most once.
    fn features(self, scene: &Scene) -> (SceneFeatures, SceneFeatures) {
        let general = SceneFeatures::general();
        match self {
            Specialise::ToScene => {
                let of_scene = SceneFeatures::of(scene);
                (of_scene, of_scene)
            }
            Specialise::PlanOnly => (SceneFeatures::of(scene), general),
            Specialise::General => (general, general),
        }
    }
}

impl Pipeline {
    /// Loads `path` with the plugins drawing `host`'s scene and `params` for the file's
    /// parameters.
    pub fn load(
        path: &Path,
        host: Arc<Host>,
        outputs: &[&str],
        specialise: Specialise,
        params: &GraphParams,
    ) -> Result<Self, FrameError> {
        Self::load_with(path, host, outputs, specialise, |registry| {
            load_file_with(path, registry, params).map_err(|e| file_error(path, e))
        })
    }

    /// Loads `text` as if it were the file `path` (relative shader paths resolve from
    /// there): for variants of a file made by rewriting it.
    pub fn from_text(
        path: &Path,
        text: &str,
        host: Arc<Host>,
        outputs: &[&str],
        specialise: Specialise,
        params: &GraphParams,
    ) -> Result<Self, FrameError> {
        Self::load_with(path, host, outputs, specialise, |registry| {
            load_str_with(path, text, registry, params).map_err(FrameError::Pipeline)
        })
    }

    /// `load` with the registry `specialise` calls for.
    fn load_with(
        path: &Path,
        host: Arc<Host>,
        outputs: &[&str],
        specialise: Specialise,
        load: impl FnOnce(&Registry) -> Result<LoadedGraph, FrameError>,
    ) -> Result<Self, FrameError> {
        let (features, shader_features) = specialise.features(&host.scene);
        let background = host.overrides.background;
        let environment = SceneFeatures::of(&host.scene).environment;
        if background == Some(Background::Environment) && !environment {
            return Err(FrameError::NoEnvironment {
                scene: host.scene.name.clone(),
            });
        }
        let features = host.overrides.applied_to(features, environment);
        let scene = host.scene.clone();
        let loaded = load(&registry_for(Some(host), specialise.variants()))?;
        let mut pipeline = Self::keep(path, loaded, outputs, (features, shader_features), scene)?;
        pipeline.background = background;
        Ok(pipeline)
    }

    fn keep(
        path: &Path,
        mut loaded: LoadedGraph,
        outputs: &[&str],
        (features, shader_features): (SceneFeatures, SceneFeatures),
        scene: Arc<Scene>,
    ) -> Result<Self, FrameError> {
        let offered = loaded.outputs().iter().map(|o| o.to_string()).collect();
        loaded
            .keep_outputs(outputs)
            .map_err(|source| FrameError::NotAnOutput {
                pipeline: path.to_path_buf(),
                source,
            })?;
        Ok(Pipeline {
            path: path.to_path_buf(),
            loaded,
            outputs: outputs.iter().map(|o| o.to_string()).collect(),
            offered,
            features,
            shader_features,
            scene,
            background: None,
        })
    }
}

/// An unreadable file is an I/O problem; anything else in it makes it invalid.
fn file_error(path: &Path, errors: FileErrors) -> FrameError {
    let unreadable = errors.0.iter().find_map(|e| match &e.kind {
        ErrorKind::Unreadable { reason } if Path::new(&e.location.path) == path => {
            Some(reason.clone())
        }
        _ => None,
    });
    match unreadable {
        Some(reason) => FrameError::PipelineUnreadable {
            path: path.to_path_buf(),
            reason,
        },
        None => FrameError::Pipeline(errors),
    }
}
