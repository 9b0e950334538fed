//! What the deferred passes share, below them: the state every plugin of a registry shares
//! and how a pass hands over its recording ([`plugin`]), the textures in a pass's slots
//! ([`textures`]), the light passes' optional ambient-occlusion input ([`ao`]), the scene
//! passes' background fill ([`background`]), the depth convention ([`depth`]), where a
//! pass draws ([`extent`]), the edge detectors two passes use ([`edge_detection`]), the
//! full-screen draw five passes set up ([`fullscreen`]) and its compute counterpart
//! ([`fullscreen_compute`]), the passes that draw the scene's meshes ([`scene_draw`]),
//! the G-buffer layouts a lighting pass reads ([`gbuffer_layout`]) and the material layers'
//! targets in them ([`gbuffer_layers`]), a pass made for the optional textures its plan
//! keeps ([`optional_targets`]), the G-buffer's pose offset ([`pose_offset`]), the opaque
//! depth the
//! passes after them read ([`opaque_depth`]), the lean G-buffer's emission encoding
//! ([`rgb9e5`]), the compute raster's occlusion culling slots ([`occlusion`]), the slot of
//! a shadow atlas kept while nothing moves ([`shadow_cache`]), a pass parameter that turns
//! work on or off ([`switch`]) and, with feature `gpu`, the device
//! helpers of their recordings ([`gpu`]). Nothing here imports a pass.

pub(crate) mod ao;
pub(crate) mod background;
pub(crate) mod depth;
pub(crate) mod edge_detection;
pub(crate) mod extent;
pub(crate) mod fullscreen;
pub(crate) mod fullscreen_compute;
pub(crate) mod gbuffer_layers;
pub(crate) mod gbuffer_layout;
#[cfg(feature = "gpu")]
pub(crate) mod gpu;
pub(crate) mod occlusion;
pub(crate) mod opaque_depth;
pub(crate) mod optional_targets;
pub(crate) mod plugin;
pub(crate) mod pose_offset;
pub(crate) mod rgb9e5;
pub(crate) mod scene_draw;
pub(crate) mod shadow_cache;
pub(crate) mod shadow_depth;
pub(crate) mod shadows;
pub(crate) mod switch;
pub(crate) mod textures;
pub(crate) mod visibility_samples;
