//! Compiling a graph into a [`Plan`], without a GPU. [`Graph::compile_for`] reads as the
//! list of phases; each phase is one file.

mod conditions;
mod cull;
mod formats;
mod history;
mod lifetimes;
mod load_store;
mod order;
mod physical;
mod usage;
mod validate;
mod versions;

use crate::condition::Features;
use crate::error::{GraphError, GraphErrors};
use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};
use crate::plan::{CulledPass, HistoryEdge, MemoryReport, Plan, PlannedPass, PlannedResource};
use crate::profile::{color_bytes_per_sample, DeviceProfile};
use crate::resource::{texel_bytes, ResourceDesc, TextureShape};

use conditions::Conditioned;
use cull::Live;
use load_store::Attachments;
use physical::Physical;
use usage::Usages;
use versions::Versions;

/// What a compile is for: the output size relative textures resolve against, and the
/// device whose limits and formats the graph must fit. The scene's features are the
/// other input, an argument of [`Graph::compile_for`]: a field here would break every
/// caller that writes these options out in full.
#[derive(Clone, Debug)]
pub struct CompileOptions {
    /// Width and height in texels of the frame's output: what [`Size::Relative`] sizes
    /// and per-sample buffers resolve against.
    ///
    /// [`Size::Relative`]: crate::Size::Relative
    pub output_size: (u32, u32),
    /// The device the plan must run on: its limits, features and format capabilities.
    /// An error, not a panic, when the graph does not fit it.
    pub profile: DeviceProfile,
}

impl Default for CompileOptions {
    /// 1920x1080 against the WebGPU defaults: what a graph file must fit to run anywhere.
    fn default() -> Self {
        Self {
            output_size: (1920, 1080),
            profile: DeviceProfile::webgpu(),
        }
    }
}

impl Graph {
    /// Compiles the graph for `options` with no feature set: every `!feature` condition
    /// holds and no `feature` condition does. See [`compile_for`](Self::compile_for).
    pub fn compile(&self, options: &CompileOptions) -> Result<Plan, GraphErrors> {
        self.compile_for(options, &Features::new())
    }

    /// Compiles the graph for `options` as `features` make it. Returns every error found,
    /// each naming its pass and resource; a graph that compiles is one the executor can
    /// run on a device that matches the profile. The graph itself is not changed.
    ///
    /// Features the graph does not declare are ignored, so a caller can pass everything
    /// its scene has and each graph sees the features it cares about; the plan records
    /// the ones it saw.
    pub fn compile_for(
        &self,
        options: &CompileOptions,
        features: &Features,
    ) -> Result<Plan, GraphErrors> {
        let features = self.relevant(&options.profile.conditions(features));
        let mut conditioned = conditions::apply(self, &features);
        conditioned.graph.size_buffers(options.output_size);
        let graph = &conditioned.graph;
        let shapes = graph.resolve_shapes(options.output_size, &options.profile);
        let versions = Versions::index(graph);
        self.validate(&conditioned, &shapes, &versions, &options.profile)?;
        let live = cull::cull(graph, &versions);
        let order = order::order(graph, &versions, &live).map_err(|e| GraphErrors(vec![e]))?;
        let lifetimes = lifetimes::lifetimes(graph, &order);
        let attachments = load_store::infer(graph, &versions, &live, &shapes);
        let usages = usage::derive(graph, &versions, &live, &attachments, &options.profile);
        let history = history::edges(graph, &versions, &live, &order, &shapes, &usages);
        let physical = physical::plan(graph, &shapes, &lifetimes, &usages, &history);
        Ok(self.assemble(
            options,
            features,
            Assembly {
                conditioned,
                shapes,
                live,
                order,
                lifetimes,
                attachments,
                usages,
                physical,
                history,
            },
        ))
    }

    /// Buffers sized per sample get their size in bytes for `output` (and `per_sample`
    /// 0), so the later phases and the plan see bytes only.
    fn size_buffers(&mut self, output: (u32, u32)) {
        for resource in &mut self.resources {
            if let ResourceDesc::Buffer(b) = &mut resource.desc {
                b.size = b.bytes(output);
                b.per_sample = 0;
            }
        }
    }

    /// What one sample of the buffers sized per sample among `writes` holds, as declared
    /// (the compiled graph has their sizes in bytes): a compute pass's per-sample
    /// storage, as a render pass's attachments are.
    fn per_sample_bytes_written(&self, writes: &[(ResourceId, u32)]) -> u32 {
        writes
            .iter()
            .filter_map(|(r, _)| self.resources[r.index()].buffer())
            .map(|b| b.per_sample as u32)
            .sum()
    }

    /// Sizes resolved against the output, and each texture's format: the first of its
    /// formats the profile can make with its sample count (else the first, which
    /// validation then rejects with the reason). Called on the conditioned graph, where
    /// conditional formats are settled: a chosen one replaced format and fallback.
    fn resolve_shapes(
        &self,
        output: (u32, u32),
        profile: &DeviceProfile,
    ) -> Vec<Option<TextureShape>> {
        self.resources
            .iter()
            .map(|r| match &r.desc {
                ResourceDesc::Texture(t) => {
                    let (width, height) = t.size.resolve(output);
                    let format = t
                        .formats()
                        .find(|&f| profile.can_make(f, t.samples))
                        .unwrap_or(t.format);
                    Some(TextureShape {
                        format,
                        width,
                        height,
                        samples: t.samples,
                        mips: t.mips,
                        layers: t.layers,
                    })
                }
                ResourceDesc::Buffer(_) => None,
            })
            .collect()
    }

    /// Mistakes in declaring and in conditions come first and alone: the checks of the
    /// conditioned graph would only repeat them in other words.
    fn validate(
        &self,
        conditioned: &Conditioned,
        shapes: &[Option<TextureShape>],
        versions: &Versions,
        profile: &DeviceProfile,
    ) -> Result<(), GraphErrors> {
        let mut errors: Vec<GraphError> = self.declare_errors.clone();
        errors.extend(conditioned.errors.iter().cloned());
        if errors.is_empty() {
            history::check(conditioned, &mut errors);
            validate::resources(self, conditioned, shapes, versions, profile, &mut errors);
            validate::passes(conditioned, shapes, versions, profile, &mut errors);
        }
        if errors.is_empty() {
            Ok(())
        } else {
            Err(GraphErrors(errors))
        }
    }

    /// The plan, from the conditioned graph (live passes read through dropped ones)
    /// and the declared one (dropped passes show what they would have read and written).
    fn assemble(&self, options: &CompileOptions, features: Features, a: Assembly) -> Plan {
        let graph = &a.conditioned.graph;
        let passes = a
            .order
            .iter()
            .map(|&id| {
                let pass = &graph.passes[id.index()];
                let Attachments {
                    color,
                    depth_stencil,
                } = &a.attachments[id.index()];
                let (reads, writes) = pass.versions();
                let stored_in_buffers = self.per_sample_bytes_written(&writes);
                PlannedPass {
                    id,
                    name: pass.name.clone(),
                    kind: pass.kind,
                    reads,
                    writes,
                    color_bytes_per_sample: color_bytes_per_sample(
                        color
                            .iter()
                            .filter_map(|c| a.shapes[c.resource.index()].map(|s| s.format)),
                    ),
                    stored_bytes_per_sample: color
                        .iter()
                        .map(|c| c.resource)
                        .chain(depth_stencil.as_ref().map(|d| d.resource))
                        .filter_map(|r| a.shapes[r.index()].map(|s| texel_bytes(s.format) as u32))
                        .sum::<u32>()
                        + stored_in_buffers,
                    color: color.clone(),
                    depth_stencil: depth_stencil.clone(),
                    workgroups: pass.workgroups.clone(),
                    dropped_reads: a.conditioned.dropped_reads[id.index()].clone(),
                    origin: pass.origin.clone(),
                }
            })
            .collect();
        let culled = a
            .conditioned
            .passes
            .iter()
            .zip(&a.live.pass_reasons)
            .enumerate()
            .filter_map(|(i, (dropped, culled))| {
                let pass = match dropped {
                    Some(_) => &self.passes[i],
                    None => &graph.passes[i],
                };
                let (reads, writes) = pass.versions();
                dropped
                    .as_ref()
                    .or(culled.as_ref())
                    .map(|reason| CulledPass {
                        id: PassId(i as u32),
                        name: pass.name.clone(),
                        kind: pass.kind,
                        reason: reason.clone(),
                        dropped: dropped.is_some(),
                        reads,
                        writes,
                    })
            })
            .collect();
        let resources: Vec<PlannedResource> = graph
            .resources
            .iter()
            .enumerate()
            .map(|(r, node)| PlannedResource {
                id: ResourceId(r as u32),
                name: node.name.clone(),
                kind: match node.desc {
                    ResourceDesc::Texture(_) => crate::handle::Kind::Texture,
                    ResourceDesc::Buffer(_) => crate::handle::Kind::Buffer,
                },
                origin: node.origin,
                exported: node.exported,
                texture: a.shapes[r],
                buffer_size: node.buffer().map(|b| b.size),
                texture_usage: a.usages.texture[r],
                buffer_usage: a.usages.buffer[r],
                lifetime: a.lifetimes[r],
                physical: a.physical.assignment[r],
                culled: a.conditioned.resources[r]
                    .clone()
                    .or_else(|| a.live.resource_reasons[r].clone()),
                format_because: a.conditioned.formats[r].clone(),
                bytes: match (a.shapes[r], node.buffer()) {
                    (Some(shape), _) => shape.bytes(),
                    (None, Some(b)) => b.size,
                    (None, None) => 0,
                },
            })
            .collect();
        // A history's pair is two textures, the source's and the history's.
        let pairs: u64 = a.history.iter().map(|e| 2 * e.bytes).sum();
        let memory = MemoryReport {
            logical_bytes: resources
                .iter()
                .filter(|r| r.physical.is_some())
                .map(|r| r.bytes)
                .sum::<u64>()
                + pairs,
            physical_bytes: a.physical.textures.iter().map(|t| t.bytes).sum::<u64>()
                + a.physical.buffers.iter().map(|b| b.size).sum::<u64>()
                + pairs,
        };
        let mut plan = Plan {
            output_size: options.output_size,
            profile: options.profile.name.clone(),
            features: features.iter().map(str::to_owned).collect(),
            passes,
            culled,
            resources,
            textures: a.physical.textures,
            buffers: a.physical.buffers,
            memory,
            history: a.history,
            fingerprint: 0,
        };
        plan.fingerprint = history::fingerprint(&plan);
        plan
    }
}

/// Everything the phases computed, handed to [`Graph::assemble`].
struct Assembly {
    conditioned: Conditioned,
    shapes: Vec<Option<TextureShape>>,
    live: Live,
    order: Vec<PassId>,
    lifetimes: Vec<Option<(usize, usize)>>,
    attachments: Vec<Attachments>,
    usages: Usages,
    physical: Physical,
    history: Vec<HistoryEdge>,
}
