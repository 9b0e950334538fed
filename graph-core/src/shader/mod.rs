//! WGSL checked without a GPU: parsed and validated with naga, then reflected to the
//! entry points and bindings that pass plugins check their declarations against.

mod error;
mod parsed;
mod reflect;
mod wgsl;

pub use error::ShaderError;
pub use reflect::{BindingKind, Entry, Io, Number, SampleKind, ShaderBinding, Stage};
pub use wgsl::Shader;
