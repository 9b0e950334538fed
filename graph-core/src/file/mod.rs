//! Graph files: render graphs declared in RON, loaded through the same builder and
//! compile as graphs declared in code.
//!
//! ```ron
//! Graph(
//!     resources: {
//!         "hdr": Texture(format: "rgba16float", size: Relative(1.0), samples: 1),
//!         "target": ImportedTexture(format: "rgba8unorm-srgb"),
//!     },
//!     passes: [
//!         (name: "sky", plugin: "fullscreen",
//!          params: (shader: "../shaders/sky.wgsl"),
//!          outputs: { "color": "hdr" }),
//!         (name: "present", plugin: "blit",
//!          inputs: { "src": "hdr" }, outputs: { "dst": "target" }),
//!     ],
//!     outputs: ["target"],
//! )
//! ```
//!
//! Each name denotes one version of one resource and has exactly one writer. A declared
//! resource's name is the version its writer produces (for an import nobody writes, the
//! engine's contents). A slot listed in both `inputs` and `outputs` modifies what it
//! reads, and its output name names the new version. Passes may be listed in any order:
//! each is declared after the passes whose outputs it reads, file order breaking ties.
//!
//! Errors read `FILE:LINE:COL: error: MESSAGE` and name the pass and the resource.

mod any_handle;
mod compose;
mod conditions;
mod declare;
mod error;
mod line_index;
mod load;
mod loaded;
mod names;
mod order;
mod pairs;
mod param_uses;
mod params;
mod plugin;
mod plugin_error;
mod plugin_pass;
mod references;
mod registry;
mod ron_message;
mod schema;
mod shown;
mod slots;
mod source;
mod spans;
mod validate;

pub use crate::position::Position;
pub use any_handle::AnyHandle;
pub use error::{ErrorKind, FileError, FileErrors, Location};
pub use load::{declared_params, load_file, load_file_with, load_str, load_str_with};
pub use loaded::{LoadedGraph, Names, NotAnOutput};
pub use params::GraphParams;
pub use plugin::Plugin;
pub use plugin_error::PluginError;
pub use plugin_pass::{PluginPassError, Written};
pub use registry::Registry;
pub use slots::{Slots, Target};
pub use validate::{validate_dir, validate_file, validate_shader, Validated};
