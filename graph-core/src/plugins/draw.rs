//! A full-screen draw, shared by the `fullscreen` and `blit` plugins: the built-in
//! full-screen triangle as vertex stage, a fragment entry point whose `@location(n)`
//! outputs are the pass's output slots that no binding takes, in file order.

use serde::Deserialize;

use super::binding::{bind, texture_desc, BindingDecl};
use super::entry::entry_point;
use crate::builder::PassBuilder;
use crate::file::{PluginError, Slots};
use crate::handle::{Texture, TextureHandle};
use crate::shader::{Entry, Number, Shader, Stage};

/// The vertex stage: `@location(0) uv: vec2<f32>` for the fragment stage, (0, 0) at the
/// top left.
pub(crate) const FULLSCREEN_VS: &str = include_str!("fullscreen_vs.wgsl");

/// How a full-screen draw combines with what its targets hold (when it modifies them).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Blend {
    /// Overwrite.
    #[default]
    Replace,
    /// Add color and alpha.
    Additive,
    /// Premultiplied-alpha "over".
    Alpha,
}

/// Everything a full-screen draw needs to set up its pass.
pub(crate) struct Draw<'a> {
    pub shader: Shader,
    pub entry: &'a str,
    pub bindings: &'a [BindingDecl],
    // Only the record callback reads it.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub blend: Blend,
    /// Clear color of outputs written fresh.
    pub clear: [f64; 4],
}

impl Draw<'_> {
    /// Checks the shader against the slots, declares the pass's accesses and (with
    /// feature `gpu`) its record callback.
    pub fn setup(
        self,
        pass: &mut PassBuilder<'_>,
        slots: &mut Slots<'_>,
    ) -> Result<(), PluginError> {
        let shader = &self.shader;
        let entry = entry_point(shader, self.entry, Stage::Fragment)?;
        check_inputs(&entry)?;
        let bound = bind(shader, &entry, self.bindings, pass, slots)?;
        let mut targets = Vec::new();
        for slot in slots.outputs() {
            if bound.iter().any(|b| b.slot.as_deref() == Some(slot)) {
                continue;
            }
            let handle = slots.write::<Texture>(slot, |t| {
                pass.color_output(t.handle, t.color_load(self.clear))
            })?;
            targets.push((slot, handle));
        }
        check_outputs(&entry, &targets, pass, slots)?;
        #[cfg(feature = "gpu")]
        pass.render(gpu::record(
            self.shader.source().to_owned(),
            self.entry.to_owned(),
            bound,
            targets.iter().map(|(_, h)| *h).collect(),
            self.blend,
        ));
        Ok(())
    }
}

/// Each fragment input must be an output of the built-in vertex stage.
fn check_inputs(entry: &Entry<'_>) -> Result<(), PluginError> {
    let vertex = Shader::parse("built-in fullscreen_vs.wgsl", FULLSCREEN_VS)?;
    let provided = vertex
        .entry("vs_main", Stage::Vertex)
        .map(|e| e.outputs())
        .unwrap_or_default();
    match entry.inputs().into_iter().find(|io| !provided.contains(io)) {
        Some(io) => Err(PluginError::Invalid(format!(
            "fragment input @location({}) of \"{}\" is not provided by the full-screen vertex \
             stage, which passes only @location(0) uv: vec2<f32>",
            io.location,
            entry.name()
        ))),
        None => Ok(()),
    }
}

/// Each color attachment needs an output of a matching number type at its location, and
/// each output a color attachment.
fn check_outputs(
    entry: &Entry<'_>,
    targets: &[(&str, TextureHandle)],
    pass: &PassBuilder<'_>,
    slots: &Slots<'_>,
) -> Result<(), PluginError> {
    let outputs = entry.outputs();
    for ((slot, handle), location) in targets.iter().zip(0u32..) {
        let format = texture_desc(pass, *handle)?.format;
        let written = outputs.iter().find(|o| o.location == location);
        let wants = match format.sample_type(None, None) {
            Some(wgpu_types::TextureSampleType::Uint) => Number::Uint,
            Some(wgpu_types::TextureSampleType::Sint) => Number::Sint,
            _ => Number::Float,
        };
        let why = match written {
            None => format!(
                "is color attachment {location}, but \"{}\" writes no @location({location})",
                entry.name()
            ),
            Some(o) if o.number != wants => format!(
                "is color attachment {location} and holds {wants} values, but \"{}\" writes \
                 {} there",
                entry.name(),
                o.number
            ),
            Some(_) => continue,
        };
        return Err(PluginError::Slot {
            slot: (*slot).to_owned(),
            resource: slots.resource(slot).unwrap_or(slot).to_owned(),
            why,
        });
    }
    match outputs
        .iter()
        .find(|o| o.location as usize >= targets.len())
    {
        Some(o) => Err(PluginError::Invalid(format!(
            "\"{}\" writes @location({}), but the pass has {} color attachment(s): its output \
             slots that no binding takes, in file order",
            entry.name(),
            o.location,
            targets.len()
        ))),
        None => Ok(()),
    }
}

#[cfg(feature = "gpu")]
mod gpu {
    use super::{Blend, FULLSCREEN_VS};
    use crate::handle::TextureHandle;
    use crate::plugins::binding::Bound;
    use crate::plugins::gpu::{module, GpuBindings};
    use crate::record::RenderContext;

    /// Target formats and sample counts a pipeline was made for.
    type Key = Vec<(wgpu::TextureFormat, u32)>;

    /// Device objects, made on the first frame and kept.
    struct State {
        vertex: wgpu::ShaderModule,
        fragment: wgpu::ShaderModule,
        bindings: GpuBindings,
        layout: wgpu::PipelineLayout,
        pipeline: Option<(Key, wgpu::RenderPipeline)>,
    }

    pub(super) fn record(
        source: String,
        entry: String,
        bound: Vec<Bound>,
        targets: Vec<TextureHandle>,
        blend: Blend,
    ) -> impl FnMut(&mut RenderContext<'_, '_>) + 'static {
        let mut state: Option<State> = None;
        move |ctx| {
            let device = ctx.resources.device;
            let state = state.get_or_insert_with(|| {
                let bindings = GpuBindings::new(device, &bound, wgpu::ShaderStages::FRAGMENT);
                State {
                    vertex: module(device, FULLSCREEN_VS),
                    fragment: module(device, &source),
                    layout: bindings.pipeline_layout(device),
                    bindings,
                    pipeline: None,
                }
            });
            let key: Key = targets
                .iter()
                .map(|&h| ctx.resources.shape(h))
                .map(|s| (s.format, s.samples))
                .collect();
            // Formats and sample counts come from the plan, which may change between
            // frames (another profile, another output); rebuild only then.
            if state.pipeline.as_ref().is_none_or(|(k, _)| *k != key) {
                let pipeline = pipeline(device, state, &entry, &key, blend);
                state.pipeline = Some((key, pipeline));
            }
            if let Some((_, pipeline)) = &state.pipeline {
                ctx.pass.set_pipeline(pipeline);
            }
            for (group, index) in state.bindings.bind_groups(ctx.resources).iter().zip(0u32..) {
                ctx.pass.set_bind_group(index, group, &[]);
            }
            ctx.pass.draw(0..3, 0..1);
        }
    }

    fn pipeline(
        device: &wgpu::Device,
        state: &State,
        entry: &str,
        key: &Key,
        blend: Blend,
    ) -> wgpu::RenderPipeline {
        let blend = match blend {
            Blend::Replace => None,
            Blend::Additive => {
                let add = wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                };
                Some(wgpu::BlendState {
                    color: add,
                    alpha: add,
                })
            }
            Blend::Alpha => Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
        };
        let targets: Vec<Option<wgpu::ColorTargetState>> = key
            .iter()
            .map(|&(format, _)| {
                Some(wgpu::ColorTargetState {
                    format,
                    // Blending is undefined for integer formats; wgpu rejects it there.
                    blend: blend.filter(|_| {
                        format
                            .sample_type(None, None)
                            .is_some_and(|t| matches!(t, wgpu::TextureSampleType::Float { .. }))
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                })
            })
            .collect();
        let samples = key.first().map_or(1, |&(_, s)| s);
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: None,
            layout: Some(&state.layout),
            vertex: wgpu::VertexState {
                module: &state.vertex,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState {
                count: samples,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &state.fragment,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}
