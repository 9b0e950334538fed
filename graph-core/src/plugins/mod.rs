//! Built-in generic plugins, enough for graph files to be useful on their own:
//! [`Clear`], [`Copy`](struct@Copy), [`Blit`], [`Fullscreen`] (a WGSL fragment shader over the whole
//! target) and [`Compute`] (a WGSL compute shader). The shader plugins check the bindings
//! a file declares against the shader by reflection when the file loads, without a GPU.

mod binding;
mod blit;
mod clear;
mod compute;
mod copy;
mod draw;
mod entry;
mod fullscreen;
#[cfg(feature = "gpu")]
mod gpu;

pub use binding::{BindingDecl, Filter};
pub use blit::{Blit, BlitParams};
pub use clear::{Clear, ClearParams};
pub use compute::{Compute, ComputeParams, Dispatch};
pub use copy::{Copy, CopyParams};
pub use draw::Blend;
pub use fullscreen::{Fullscreen, FullscreenParams};

use crate::file::Registry;

impl Registry {
    /// A registry with the built-in generic plugins (those of [`register`]). Defined here,
    /// beside the plugins, so that the file front-end does not import them.
    pub fn with_builtins() -> Self {
        let mut registry = Self::new();
        register(&mut registry);
        registry
    }
}

/// Adds every built-in plugin to `registry`.
pub fn register(registry: &mut Registry) {
    registry
        .register(Clear)
        .register(Copy)
        .register(Blit)
        .register(Fullscreen)
        .register(Compute);
}
