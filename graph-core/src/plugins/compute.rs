//! The `compute` plugin; its contract is on [`Compute`].

use serde::Deserialize;

use super::binding::{bind, BindingDecl, Source};
use super::entry::entry_point;
use crate::builder::PassBuilder;
use crate::file::{Plugin, PluginError, Slots};
use crate::handle::TextureHandle;
use crate::pass::PassKind;
use crate::shader::Stage;

/// `compute`: a compute pass running a WGSL entry point from a file.
///
/// ```ron
/// (name: "exposure", plugin: "compute",
///  params: (
///      shader: "../shaders/exposure.wgsl",   // relative to the graph file
///      entry: "main",                        // the default
///      dispatch: PerTexel("out"),            // or Workgroups(8, 8, 1)
///      bindings: [Slot(binding: 0, slot: "in"), Slot(binding: 1, slot: "out")],
///  ),
///  inputs: { "in": "hdr" },
///  outputs: { "out": "hdr_exposed" })
/// ```
///
/// `PerTexel(slot)` runs one invocation per texel of the texture bound to `slot`: the
/// workgroup counts are its size divided by the entry point's `@workgroup_size`, rounded
/// up (layers count as depth). Every slot must be bound (see [`BindingDecl`]).
pub struct Compute;

/// `compute`'s parameters.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ComputeParams {
    /// WGSL file, relative to the graph file.
    pub shader: String,
    /// The compute entry point; `main` by default.
    #[serde(default = "main")]
    pub entry: String,
    /// How many workgroups to run.
    pub dispatch: Dispatch,
    /// What the shader's bindings are bound to, checked against the shader when the file
    /// loads.
    #[serde(default)]
    pub bindings: Vec<BindingDecl>,
}

fn main() -> String {
    "main".into()
}

/// How many workgroups a dispatch runs.
#[derive(Clone, Debug, Deserialize)]
pub enum Dispatch {
    /// Enough to cover every texel of the texture bound to this slot.
    PerTexel(String),
    /// Exactly these counts, each from 1 to 65,535 (WebGPU's default limit).
    Workgroups(u32, u32, u32),
}

/// [`Dispatch`] with the slot resolved to the texture bound there.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))] // Only the record callback reads it.
#[derive(Copy, Clone, Debug)]
enum Workgroups {
    PerTexel(TextureHandle, [u32; 3]),
    Fixed([u32; 3]),
}

impl Plugin for Compute {
    const NAME: &'static str = "compute";
    type Params = ComputeParams;

    fn kind(&self, _: &ComputeParams) -> PassKind {
        PassKind::Compute
    }

    fn setup(
        &self,
        params: ComputeParams,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let shader = slots.shader(&params.shader)?;
        let entry = entry_point(&shader, &params.entry, Stage::Compute)?;
        let bound = bind(&shader, &entry, &params.bindings, pass, slots)?;
        pass.workgroup(entry.workgroup());
        let workgroups = match params.dispatch {
            Dispatch::Workgroups(x, y, z) => Workgroups::Fixed(fixed_counts([x, y, z])?),
            Dispatch::PerTexel(slot) => {
                let texture = bound.iter().find_map(|b| match b.source {
                    Source::Texture(handle, _) if b.slot.as_deref() == Some(&slot) => Some(handle),
                    _ => None,
                });
                let Some(texture) = texture else {
                    return Err(PluginError::Invalid(format!(
                        "dispatch is PerTexel(\"{slot}\"), but no binding binds a texture \
                         from slot \"{slot}\""
                    )));
                };
                Workgroups::PerTexel(texture, entry.workgroup_size())
            }
        };
        #[cfg(feature = "gpu")]
        pass.compute(gpu::record(
            shader.source().to_owned(),
            params.entry,
            bound,
            workgroups,
        ));
        // Without a device nothing records; the dispatch was checked all the same.
        #[cfg(not(feature = "gpu"))]
        let _ = workgroups;
        Ok(())
    }
}

/// The most workgroups a dispatch may run per dimension: WebGPU's default
/// `max_compute_workgroups_per_dimension`, which every device offers (a graph file that
/// needs more would not be portable).
pub const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65_535;

/// `Workgroups(x, y, z)` checked: at least 1 (a dispatch of none draws nothing, silently)
/// and at most [`MAX_WORKGROUPS_PER_DIMENSION`] (more fails on the device).
fn fixed_counts(counts: [u32; 3]) -> Result<[u32; 3], PluginError> {
    for (axis, count) in ["x", "y", "z"].into_iter().zip(counts) {
        if count == 0 || count > MAX_WORKGROUPS_PER_DIMENSION {
            return Err(PluginError::Invalid(format!(
                "dispatch Workgroups({}, {}, {}) has {count} in {axis}: each count must be \
                 from 1 to {MAX_WORKGROUPS_PER_DIMENSION}",
                counts[0], counts[1], counts[2]
            )));
        }
    }
    Ok(counts)
}

#[cfg(feature = "gpu")]
mod gpu {
    use super::Workgroups;
    use crate::plugins::binding::Bound;
    use crate::plugins::gpu::{module, GpuBindings};
    use crate::record::ComputeContext;

    /// Device objects, made on the first frame and kept.
    struct State {
        bindings: GpuBindings,
        pipeline: wgpu::ComputePipeline,
    }

    pub(super) fn record(
        source: String,
        entry: String,
        bound: Vec<Bound>,
        workgroups: Workgroups,
    ) -> impl FnMut(&mut ComputeContext<'_, '_>) + 'static {
        let mut state: Option<State> = None;
        move |ctx| {
            let device = ctx.resources.device;
            let state = state.get_or_insert_with(|| {
                let bindings = GpuBindings::new(device, &bound, wgpu::ShaderStages::COMPUTE);
                let module = module(device, &source);
                let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: None,
                    layout: Some(&bindings.pipeline_layout(device)),
                    module: &module,
                    entry_point: Some(&entry),
                    compilation_options: Default::default(),
                    cache: None,
                });
                State { bindings, pipeline }
            });
            ctx.pass.set_pipeline(&state.pipeline);
            for (group, index) in state.bindings.bind_groups(ctx.resources).iter().zip(0u32..) {
                ctx.pass.set_bind_group(index, group, &[]);
            }
            let [x, y, z] = match workgroups {
                Workgroups::Fixed(counts) => counts,
                Workgroups::PerTexel(texture, size) => {
                    let shape = ctx.resources.shape(texture);
                    let texels = [shape.width, shape.height, shape.layers];
                    [0, 1, 2].map(|i| texels[i].div_ceil(size[i]))
                }
            };
            ctx.pass.dispatch_workgroups(x, y, z);
        }
    }
}
