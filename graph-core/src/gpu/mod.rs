//! Execution on a wgpu device (feature `gpu`).

mod context;

pub use context::{ComputeContext, FrameResources, RenderContext, TransferContext};
