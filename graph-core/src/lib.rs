//! A render graph on wgpu.
//!
//! Three phases, as in the best frame graphs:
//! 1. **Declare** with [`GraphBuilder`]: resources are virtual, handles are typed and
//!    versioned, and passes state how they access each resource.
//! 2. **Compile** with [`Graph::compile`], without a GPU: validation against a
//!    [`DeviceProfile`], culling, ordering, lifetimes, usages, load/store, physical plan.
//!    The resulting [`Plan`] is plain data that explains itself. Passes and resources
//!    may carry a [`Condition`] over named features; [`Graph::compile_for`] a feature
//!    set drops what does not apply first, and a [`PlanCache`] keeps one plan per set.
//! 3. **Execute** (feature `gpu`) with [`gpu::Executor`] a [`CompiledGraph`], a graph
//!    bound to its plans: pooled allocation, the inferred render-pass setup, per-pass
//!    timings, and record callbacks that reach only the resources their pass declared.
//!
//! Graphs can also be declared in RON files through registered [`file::Plugin`]s.

mod access;
mod builder;
mod compile;
mod compiled;
mod condition;
mod error;
mod graph;
mod handle;
mod pass;
mod plan;
mod plan_cache;
mod position;
mod profile;
#[cfg(feature = "gpu")]
mod record;
mod resource;

pub mod bounded_read;
pub mod embedded;
pub mod explain;
pub mod file;
pub mod folders;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod plugins;
pub mod shader;
pub mod synthetic;

pub use access::{
    Access, Aspect, AspectAccess, BufferRole, ByFormat, ColorLoad, Role, TextureRole,
};
pub use builder::{GraphBuilder, PassBuilder};
pub use compile::CompileOptions;
pub use compiled::CompiledGraph;
pub use condition::{
    is_device_condition, Condition, ConditionError, DeviceTrait, Features, Literal,
    DEVICE_CONDITIONS,
};
pub use error::{GraphError, GraphErrors};
pub use graph::Graph;
pub use handle::{
    Buffer, BufferHandle, Handle, Kind, PassId, ResourceId, ResourceKind, Texture, TextureHandle,
};
pub use pass::PassKind;
pub use pass::{PassNode, Workgroup};
pub use plan::{
    ColorAttachment, CulledPass, DepthStencilAttachment, Load, MemoryReport, Ops, PhysicalBuffer,
    PhysicalTexture, Plan, PlannedPass, PlannedResource, Store,
};
pub use plan_cache::{Compile, PlanCache, PlanKey};
pub use profile::{color_bytes_per_sample, color_target_cost, DeviceProfile};
#[cfg(feature = "gpu")]
pub use record::Record;
pub use resource::{
    texel_bytes, BufferDesc, Origin, ResourceDesc, ResourceNode, Size, TextureDesc, TextureShape,
};

pub use wgpu_types as types;
