//! Execution on a wgpu device (feature `gpu`): opening a headless device
//! ([`Gpu::open`]), running compiled plans ([`Executor`]) with engine-owned resources
//! ([`Imports`]), reading results back ([`read_texture`]), and what frames leave behind
//! ([`DeviceObjects`], [`resident_bytes`]).

mod device;
mod error_scopes;
mod executor;
mod footprint;
mod history;
mod imports;
mod pool;
mod readback;
mod timing;

pub use crate::record::{ComputeContext, FrameResources, RenderContext, TransferContext};
pub use device::{
    is_lavapipe, list_adapters, AdapterChoice, AdapterSummary, DeviceError, DeviceLoss,
    EmptyChoice, Gpu, LossWatch, COMMON_FORMATS,
};
pub use executor::{ExecuteError, Executor, FrameReport, LostAt, PassTiming};
pub use footprint::{resident_bytes, DeviceObjects};
pub use imports::{ImportError, ImportKey, Imports};
pub use pool::{PoolStats, KEEP_FRAMES};
pub use readback::{read_buffer, read_rgba16f, read_rgba8, read_texture, ReadbackError};
