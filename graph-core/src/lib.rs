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
//!
//! # Declaring and compiling, without a GPU
//!
//! Resources are declared first, then passes that access them. Every access verb that
//! writes returns the handle of the new version, and reading an older version orders the
//! reader before the write: the graph's order, lifetimes, usages and load/store operations
//! all follow from these declarations.
//!
//! ```
//! use rgraph_core::types::{TextureFormat, TextureUsages};
//! use rgraph_core::{ColorLoad, CompileOptions, GraphBuilder, Load, TextureDesc};
//!
//! let mut g = GraphBuilder::new();
//! let hdr = g.create_texture("hdr", TextureDesc::new(TextureFormat::Rgba16Float));
//! let target = g.import_texture("target", TextureDesc::new(TextureFormat::Rgba8UnormSrgb));
//!
//! // The scene clears `hdr` and draws into it; `hdr` is now the version it wrote.
//! let mut scene = g.add_render_pass("scene");
//! let hdr = scene.color_output(hdr, ColorLoad::Clear([0.0, 0.0, 0.0, 1.0]));
//!
//! // Nothing reads what this pass writes, so the compiler culls it.
//! let unused = g.create_texture("unused", TextureDesc::new(TextureFormat::Rgba8Unorm));
//! g.add_render_pass("debug").color_output(unused, ColorLoad::Clear([0.0; 4]));
//!
//! // Tone mapping samples `hdr` and draws every texel of the engine's target.
//! let mut tonemap = g.add_render_pass("tonemap");
//! tonemap.sampled(hdr);
//! tonemap.color_output(target, ColorLoad::Overwrite);
//!
//! let graph = g.build();
//! let options = CompileOptions { output_size: (1280, 720), ..CompileOptions::default() };
//! let plan = graph.compile(&options)?;
//!
//! let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
//! assert_eq!(order, ["scene", "tonemap"]);
//! assert_eq!(plan.culled[0].name, "debug");
//! // Usages come from the accesses: drawn into, then sampled.
//! let usage = plan.find("hdr").unwrap().texture_usage;
//! assert_eq!(usage, TextureUsages::RENDER_ATTACHMENT | TextureUsages::TEXTURE_BINDING);
//! // The scene's clear is its load operation.
//! assert!(matches!(plan.passes[0].color[0].ops.load, Load::Clear(_)));
//! # Ok::<(), rgraph_core::GraphErrors>(())
//! ```
//!
//! Mistakes are not panics: declaring records them and [`Graph::compile`] returns them
//! all, each naming its pass and resource ([`GraphError`]).
//!
//! # Executing (feature `gpu`)
//!
//! A pass records its commands in a callback that runs once per frame. It finds the
//! frame's physical resources through the handles it declared, and keeps what it creates
//! (pipelines) across frames; the executor owns and pools the graph's textures and
//! buffers. See `examples/builder_only.rs` for a complete engine with two passes of its
//! own.
//!
//! ```no_run
//! use rgraph_core::gpu::{read_rgba8, AdapterChoice, Executor, Gpu, Imports};
//! use rgraph_core::types::TextureFormat;
//! use rgraph_core::{ColorLoad, CompileOptions, CompiledGraph, GraphBuilder, TextureDesc};
//!
//! let gpu = Gpu::open(&AdapterChoice::from_env())?;
//! let mut g = GraphBuilder::new();
//! let color = g.create_texture("color", TextureDesc::new(TextureFormat::Rgba8Unorm));
//! let mut pass = g.add_render_pass("clear");
//! let color = pass.color_output(color, ColorLoad::Clear([1.0, 0.0, 0.0, 1.0]));
//! // The clear is the attachment's load operation: there is nothing to draw.
//! pass.render(|_ctx| {});
//! // Exported: kept past the frame, so it can be read back.
//! g.export(color);
//!
//! let options = CompileOptions { output_size: (64, 64), profile: gpu.profile() };
//! let mut compiled = CompiledGraph::new(g.build(), &options)?;
//! let mut executor = Executor::new(&gpu);
//! for _ in 0..3 {
//!     // The first frame allocates the texture, later ones reuse it.
//!     let report = executor.execute(&mut compiled, &Imports::new())?;
//!     println!("textures allocated: {}", report.textures_allocated);
//! }
//! let texture = executor.texture(compiled.plan(), color.id()).expect("exported");
//! assert_eq!(read_rgba8(&gpu.device, &gpu.queue, texture)?[0], [255, 0, 0, 255]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![deny(missing_docs)]

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
    Access, Aspect, AspectAccess, BufferRole, ByFormat, ColorLoad, DroppedRead, Role, TextureRole,
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
    ColorAttachment, CulledPass, DepthStencilAttachment, HistoryEdge, Load, MemoryReport, Ops,
    PhysicalBuffer, PhysicalTexture, Plan, PlannedPass, PlannedResource, Store,
};
pub use plan_cache::{Compile, PlanCache};
pub use profile::{color_bytes_per_sample, color_target_cost, DeviceProfile};
#[cfg(feature = "gpu")]
pub use record::Record;
pub use resource::{
    texel_bytes, BufferDesc, Origin, ResourceDesc, ResourceNode, Size, TextureDesc, TextureShape,
};

pub use wgpu_types as types;
