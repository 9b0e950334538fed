//! What the host application hands the deferred plugins: the scene to draw and the
//! per-render overrides a command line or an engine UI sets.
//!
//! Graph files name plugins and their parameters; the scene is not a graph resource
//! (its geometry and lights are uploaded by the plugins that use them, on their first
//! frame, from the device they record with). A registry made with `host: None` declares
//! the same passes and validates the same graphs, for build scripts and CI; executing
//! such a graph draws no geometry.

use std::sync::Arc;

use crate::scene::Scene;

/// The scene and overrides every deferred plugin of one registry shares.
pub struct Host {
    pub scene: Arc<Scene>,
    pub overrides: Overrides,
}

/// Values that, when set, replace what the graph file's parameters say.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Tone-mapping operator name: "none", "reinhard" or "aces".
    pub tonemap: Option<String>,
    /// Exposure applied before tone mapping.
    pub exposure: Option<Exposure>,
}

/// How bright the image is made before tone mapping.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Exposure {
    /// A multiplier, finite and positive.
    Fixed(f32),
    /// Metered from each frame's resolved HDR image by the `auto_exposure` pass, which a
    /// pipeline runs under the condition `auto_exposure` (set by the host's choice, see
    /// [`crate::analysis::Features::auto_exposure`]); its `tonemap` pass reads the result.
    Auto,
}
