//! Conditions over named features: what lets one graph serve many scenes.
//!
//! A pass or a resource may carry a [`Condition`], a conjunction of features that must be
//! set (`spot_lights`) or unset (`!unlit_only`). The graph declares the feature names its
//! conditions may use; the caller compiles for a set of [`Features`] (what its scene
//! needs), and the first compile phase drops what does not apply, saying why. A texture
//! may also carry conditional formats ([`TextureDesc::format_if`]), which the same phase
//! settles.
//!
//! [`TextureDesc::format_if`]: crate::TextureDesc::format_if
//!
//! Conditions are conjunctions only: a disjunction is two passes with exclusive
//! conditions (`a` and `!a`), which may then write the same version, one at a time.

mod device;
mod expr;
mod features;
mod parse;

pub use device::{is_device_condition, DeviceTrait, DEVICE_CONDITIONS};
pub use expr::{Condition, Literal};
pub use features::Features;
pub use parse::ConditionError;
