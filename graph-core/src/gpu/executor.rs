//! Executing a [`CompiledGraph`]'s plan: physical resources from the pool, each pass begun with
//! the planned attachments and load/store operations, the record callbacks, one submit,
//! GPU timestamps per pass. wgpu inserts the barriers; the plan's usages and order are
//! what make them right.

use std::collections::HashMap;
use std::time::Instant;

use crate::access::{Aspect, Role, TextureRole};
use crate::compiled::CompiledGraph;
use crate::graph::Graph;
use crate::handle::ResourceId;
use crate::pass::PassKind;
use crate::plan::{Load, Ops, Plan, PlannedPass, Store};
use crate::plan_cache::Compile;
use crate::record::{
    ComputeContext, FrameObjects, FrameResources, Record, RenderContext, TransferContext,
};
use crate::resource::{format_name, texel_bytes, Origin, TextureShape};

use super::device::{DeviceLoss, ErrorLog, Gpu, LossWatch};
use super::error_scopes::ErrorScopes;
use super::history::{Carried, Histories};
use super::imports::{Binding, ImportError, Imports};
use super::pool::{make_view, Pool, PoolStats, ViewKey};
use super::timing::Timestamps;

/// Timings of one executed pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// The pass's name.
    pub name: String,
    /// The kind of wgpu pass it recorded.
    pub kind: PassKind,
    /// GPU time between the pass's begin and end stamps; `None` when the device cannot
    /// time it (no `TIMESTAMP_QUERY`, or a transfer pass without
    /// `TIMESTAMP_QUERY_INSIDE_ENCODERS`, or past the 2048 passes a query set holds).
    pub gpu_ns: Option<u64>,
    /// CPU time to begin the pass, run its record callback and end it.
    pub cpu_ns: u64,
    /// Bytes of the buffers the pass keeps for itself and used this frame
    /// ([`FrameResources::hold`]), which the plan's memory does not count.
    pub held_bytes: u64,
}

/// What one [`Executor::execute`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameReport {
    /// Executed passes, in execution order.
    pub passes: Vec<PassTiming>,
    /// From the first timed pass's begin stamp to the last one's end stamp (gaps between
    /// passes included); `None` when no pass was timed.
    pub gpu_total_ns: Option<u64>,
    /// Textures this frame had to create (0 when the pool already held them all).
    pub textures_allocated: u32,
    /// Buffers this frame had to create.
    pub buffers_allocated: u32,
    /// CPU time from the call to the submission returning: checking the imports, taking
    /// resources from the pool, recording every pass and submitting, without the wait for
    /// the GPU that follows. What a frame costs the CPU of a frame loop.
    pub record_submit_ns: u64,
}

impl FrameReport {
    /// Bytes of the buffers the frame's passes keep for themselves
    /// ([`PassTiming::held_bytes`]), beside the plan's memory.
    pub fn held_bytes(&self) -> u64 {
        self.passes.iter().map(|p| p.held_bytes).sum()
    }
}

/// What recording one pass measured, for its [`PassTiming`].
struct RecordedPass {
    cpu_ns: u64,
    held_bytes: u64,
}

/// Why a frame could not execute.
#[derive(Debug, thiserror::Error)]
pub enum ExecuteError {
    /// The plan leaves out what its own graph uses: a bug in rgraph-core's compiler.
    #[error("the plan does not provide what its graph uses ({0}); this is a bug in rgraph-core")]
    Inconsistent(String),

    /// A pass's callback could not record its work on this device ([`FrameResources::fail`]).
    #[error("pass \"{pass}\": {why}")]
    Pass {
        /// The pass, by name.
        pass: String,
        /// The reason the callback gave.
        why: String,
    },

    /// A pass's record callback is of another kind than the pass (a compute callback on a
    /// render pass): a bug in the code that declared it.
    #[error("pass \"{pass}\" is a {kind} pass but its callback records {record} commands")]
    RecordKind {
        /// The pass, by name.
        pass: String,
        /// The pass's kind.
        kind: PassKind,
        /// The callback's kind.
        record: PassKind,
    },

    /// The imports do not fit the plan: checked before the device is touched.
    #[error(transparent)]
    Import(#[from] ImportError),

    /// The device could not create a texture or buffer of the plan (out of memory, or
    /// beyond a limit the profile it was compiled for did not have). `what` names the
    /// resources it holds, its size, format and bytes; `pass` the first pass using it.
    #[error("cannot allocate {what} for pass \"{pass}\" on the device: {message}")]
    Allocation {
        /// The physical object: the resources it holds, its shape and bytes.
        what: String,
        /// The pass, by name.
        pass: String,
        /// wgpu's message.
        message: String,
    },

    /// The device was lost: destroyed, reset, or a shader ran past the driver's timeout.
    /// Everything created on it is gone; open a new device, and the compiled graph runs
    /// on a new executor there (the plugins build their device objects again on it).
    #[error(
        "the device was lost {at}: {loss}; open a new device and run the graph with a new \
         Executor on it"
    )]
    DeviceLost {
        /// When in the frame the loss was found.
        at: LostAt,
        /// The reason the device gave.
        loss: DeviceLoss,
    },

    /// A validation or out-of-memory error wgpu reported while the frame was built or
    /// submitted: in the pass named (its recording, callback included), or outside any
    /// pass. Nothing of the frame was submitted when a pass failed.
    #[error("{}", device_message(pass.as_deref(), message))]
    Device {
        /// The pass whose recording raised it, or `None` outside any pass (allocation,
        /// submission).
        pass: Option<String>,
        /// wgpu's messages, one per line.
        message: String,
    },
}

/// When a frame found its device lost.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LostAt {
    /// Before the frame began: nothing of it ran.
    Start,
    /// While the pass named was recorded: wgpu reported the loss at once (a driver error
    /// during a call).
    Pass(String),
    /// While the frame's passes (named, in order) were recorded or ran: wgpu reports most
    /// losses (a device destroyed, a GPU reset, a timeout) only once it waits for the
    /// frame, and the device does not say which pass it was running.
    Frame(Vec<String>),
}

impl std::fmt::Display for LostAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LostAt::Start => f.write_str("before the frame began"),
            LostAt::Pass(pass) => write!(f, "while pass \"{pass}\" was recorded"),
            LostAt::Frame(passes) => {
                let names: Vec<String> = passes.iter().map(|p| format!("\"{p}\"")).collect();
                write!(f, "while the frame ran (its passes: {})", names.join(", "))
            }
        }
    }
}

/// Executes plans on one device, keeping physical resources and timestamp queries
/// across frames.
///
/// Textures and buffers of the last frame stay alive until the next
/// [`execute`](Self::execute): that is how exported resources are read after a frame. The
/// engine owns what it imports; the executor only borrows it for the frame.
pub struct Executor {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pool: Pool,
    timestamps: Option<Timestamps>,
    /// Errors outside any scope, when the device was opened by [`Gpu`].
    uncaptured: Option<ErrorLog>,
    /// Whether the device was lost, when known ([`Gpu`]'s, or one given to
    /// [`watching`](Self::watching)).
    loss: Option<LossWatch>,
    /// Pool indices of the last frame's physical textures and buffers, by plan index.
    frame_textures: Vec<usize>,
    frame_buffers: Vec<usize>,
    /// The pairs of textures of the plan's histories, kept across frames.
    histories: Histories,
    /// Frames begun so far: the number the next frame's passes see
    /// ([`FrameResources::frame`]).
    frames: u64,
}

impl Executor {
    /// An executor on a device opened by [`Gpu::open`]; device errors raised outside the
    /// frame's error scopes (other threads, internal errors) are reported too, and a lost
    /// device is [`ExecuteError::DeviceLost`].
    pub fn new(gpu: &Gpu) -> Self {
        let mut executor = Self::from_device(&gpu.device, &gpu.queue).watching(gpu.loss.clone());
        executor.uncaptured = Some(gpu.errors.clone());
        executor
    }

    /// An executor on an engine's device. The engine keeps handling errors that fall
    /// outside the frame's error scopes, and the device's loss: without
    /// [`watching`](Self::watching), frames on a lost device fail with the device errors
    /// wgpu raises instead of [`ExecuteError::DeviceLost`].
    ///
    /// One process's devices must come from one `wgpu::Instance`: the plugins keep
    /// pipelines and scene buffers per device, and wgpu 30 tells devices apart by an ID
    /// each instance numbers from one, so a device of a second instance would be handed
    /// the first's objects (wgpu then panics on an unknown ID).
    pub fn from_device(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self {
            device: device.clone(),
            queue: queue.clone(),
            pool: Pool::default(),
            timestamps: Timestamps::new(device, queue),
            uncaptured: None,
            loss: None,
            frame_textures: Vec::new(),
            frame_buffers: Vec::new(),
            histories: Histories::default(),
            frames: 0,
        }
    }

    /// This executor, told by `loss` when its device is lost (an engine records into it
    /// from the callback it gave `wgpu::Device::set_device_lost_callback`): frames then
    /// fail with [`ExecuteError::DeviceLost`], naming the pass being recorded.
    pub fn watching(mut self, loss: LossWatch) -> Self {
        self.loss = Some(loss);
        self
    }

    /// Why the device was lost, once it is (and the executor is told).
    fn lost(&self) -> Option<DeviceLoss> {
        self.loss.as_ref()?.lost()
    }

    /// Runs one frame of `compiled`'s current plan, calling its graph's record callbacks,
    /// and waits for the GPU to finish it.
    ///
    /// Checks `imports` against the plan before touching the device. Validation and
    /// out-of-memory errors while recording (record callbacks included) or submitting
    /// come back as [`ExecuteError::Device`], not as panics. A record callback that looks
    /// up a resource its pass did not declare panics (see [`FrameResources`]).
    /// Invalidates what [`texture`](Self::texture) and [`buffer`](Self::buffer) returned
    /// for the previous frame: the pool may hand those objects to this frame's resources.
    pub fn execute<G: Compile>(
        &mut self,
        compiled: &mut CompiledGraph<G>,
        imports: &Imports,
    ) -> Result<FrameReport, ExecuteError> {
        let start = Instant::now();
        if let Some(loss) = self.lost() {
            let at = LostAt::Start;
            return Err(ExecuteError::DeviceLost { at, loss });
        }
        let (graph, plan) = compiled.parts();
        check_records(graph, plan)?;
        self.frames += 1;
        let bound = imports.resolve(graph, plan)?;
        // Scopes are per thread and capture everything below: resource creation, each
        // pass (which pushes its own scopes too), the submission.
        let scopes = ErrorScopes::push(&self.device);
        let carried = self.histories.begin(&self.device, plan);
        let recorded = self
            .acquire(graph, plan, &bound, &carried)
            .and_then(|objects| {
                let slots = self.timing_slots(plan);
                let (buffers, passes) = self.record(graph, plan, &objects, &slots)?;
                self.queue.submit(buffers);
                Ok((slots, passes))
            });
        let record_submit_ns = start.elapsed().as_nanos() as u64;
        let mut messages: Vec<String> = scopes.pop().into_iter().collect();
        let (slots, passes) = recorded?;
        if let Some(log) = &self.uncaptured {
            messages.extend(log.take());
        }
        let stamps = match messages.is_empty() {
            true => self.read_timestamps(&slots),
            false => Err(ExecuteError::Device {
                pass: None,
                message: messages.join("\n"),
            }),
        };
        // What a lost device fails with is its loss, not the errors that followed it.
        if let Some(loss) = self.lost() {
            if let Some(log) = &self.uncaptured {
                log.take();
            }
            let at = LostAt::Frame(plan.passes.iter().map(|p| p.name.clone()).collect());
            return Err(ExecuteError::DeviceLost { at, loss });
        }
        let stamps = stamps?;
        // Only a frame that ran hands its histories on; after a failed one the next
        // frame reads what the last good one wrote.
        self.histories.end_frame();
        Ok(self.report(plan, &slots, (passes, record_submit_ns), &stamps))
    }

    /// Forgets every history: the next frame's history resources read zeros, and their
    /// passes are told it is a reset ([`FrameResources::history_reset`]). For what the
    /// executor cannot see, such as a camera cut; it resets by itself on the first frame
    /// and whenever the plan changes (a resize, other features, another graph). The
    /// pairs of textures are made again on the next frame.
    pub fn reset_history(&mut self) {
        self.histories.reset();
    }

    /// The physical texture of an exported, graph-created texture of the last executed
    /// frame, for readback. `plan` must be the plan that frame executed (the
    /// [`CompiledGraph::plan`] it executed). `None` for
    /// resources that are not exported (their memory may hold another resource by the
    /// end of the frame), imported (the engine has them) or were not used.
    ///
    /// For the source of a history, the texture it was written into, which the next
    /// frame's history resource reads (valid until the next execution, as the others).
    pub fn texture(&self, plan: &Plan, id: ResourceId) -> Option<&wgpu::Texture> {
        if plan.history.iter().any(|e| e.source == id) {
            return self.histories.written(plan, id);
        }
        let physical = exported_physical(plan, id)?;
        plan.resources[id.index()].texture?;
        Some(self.pool.texture(*self.frame_textures.get(physical)?))
    }

    /// The physical buffer of an exported, graph-created buffer of the last executed
    /// frame. Same rules as [`texture`](Self::texture).
    pub fn buffer(&self, plan: &Plan, id: ResourceId) -> Option<&wgpu::Buffer> {
        let physical = exported_physical(plan, id)?;
        plan.resources[id.index()].buffer_size?;
        Some(self.pool.buffer(*self.frame_buffers.get(physical)?))
    }

    /// Pool counters: allocations so far and in the last frame, objects alive.
    pub fn pool_stats(&self) -> PoolStats {
        self.pool.stats()
    }

    /// Takes this frame's physical objects from the pool and gathers, for every resource a
    /// live pass accesses, its object and the views its accesses need.
    fn acquire(
        &mut self,
        graph: &Graph,
        plan: &Plan,
        bound: &HashMap<ResourceId, Binding>,
        carried: &[Carried],
    ) -> Result<FrameObjects, ExecuteError> {
        self.pool.begin_frame();
        // Labels name every resource an object holds, so wgpu's messages name them too.
        let label = |holds: &[ResourceId]| {
            let names: Vec<&str> = holds
                .iter()
                .filter_map(|id| plan.resources.get(id.index()))
                .map(|r| r.name.as_str())
                .collect();
            names.join(" | ")
        };
        // The first pass that uses any of the resources an object holds: the one a failed
        // allocation stops.
        let first_pass = |holds: &[ResourceId]| {
            let first = holds
                .iter()
                .filter_map(|id| plan.resources.get(id.index())?.lifetime)
                .map(|(first, _)| first)
                .min();
            first
                .and_then(|i| plan.passes.get(i))
                .map_or_else(String::new, |p| p.name.clone())
        };
        // Cleared first: after a failed allocation, nothing of an earlier frame is readable.
        self.frame_textures.clear();
        self.frame_buffers.clear();
        let frame_textures = plan
            .textures
            .iter()
            .map(|t| {
                let resources = label(&t.holds);
                self.pool
                    .acquire_texture(&self.device, t.shape, t.usage, || resources.clone())
                    .map_err(|message| ExecuteError::Allocation {
                        what: format!("texture \"{resources}\" ({})", describe_shape(&t.shape)),
                        pass: first_pass(&t.holds),
                        message,
                    })
            })
            .collect::<Result<_, _>>()?;
        let frame_buffers = plan
            .buffers
            .iter()
            .map(|b| {
                let resources = label(&b.holds);
                self.pool
                    .acquire_buffer(&self.device, b.size, b.usage, || resources.clone())
                    .map_err(|message| ExecuteError::Allocation {
                        what: format!("buffer \"{resources}\" ({} bytes)", b.size),
                        pass: first_pass(&b.holds),
                        message,
                    })
            })
            .collect::<Result<_, _>>()?;
        self.frame_textures = frame_textures;
        self.frame_buffers = frame_buffers;

        let mut objects = FrameObjects::default();
        // A history reads one texture of its pair, its source writes the other.
        let mut paired: HashMap<ResourceId, &wgpu::Texture> = HashMap::new();
        for c in carried {
            paired.insert(c.source, &c.current);
            paired.insert(c.history, &c.previous);
            if c.reset {
                objects.resets.insert(c.history);
            }
        }
        for planned_pass in &plan.passes {
            let pass = &graph.passes[planned_pass.id.index()];
            let kept = pass.accesses.iter().filter(|a| !planned_pass.drops(a));
            for access in kept {
                let planned = &plan.resources[access.resource.index()];
                let mismatch = || {
                    ExecuteError::Inconsistent(format!(
                        "pass \"{}\" uses \"{}\", which the plan does not allocate",
                        pass.name, planned.name
                    ))
                };
                // Imported resources have no physical index; the plan's is the pool's.
                let pooled = match planned.origin {
                    Origin::Transient => planned.physical,
                    Origin::Imported | Origin::History { .. } => None,
                };
                let bound = bound.get(&planned.id);
                let paired = paired.get(&planned.id).copied();
                match access.role {
                    Role::Buffer(_) => {
                        let buffer = match (pooled, bound) {
                            (Some(i), _) => self
                                .pool
                                .buffer(*self.frame_buffers.get(i).ok_or_else(mismatch)?)
                                .clone(),
                            (None, Some(Binding::Buffer(b))) => b.clone(),
                            _ => return Err(mismatch()),
                        };
                        objects.buffers.insert(planned.id, buffer);
                    }
                    Role::Texture(role) => {
                        let source = match (paired, pooled, bound) {
                            (Some(t), _, _) => Source::Texture(t),
                            (None, Some(i), _) => {
                                Source::Pooled(*self.frame_textures.get(i).ok_or_else(mismatch)?)
                            }
                            (None, None, Some(Binding::Texture(t))) => Source::Texture(t),
                            (None, None, Some(Binding::View(v))) => Source::View(v),
                            _ => return Err(mismatch()),
                        };
                        let shape = planned.texture.ok_or_else(mismatch)?;
                        let texture = match source {
                            Source::Pooled(i) => self.pool.texture(i).clone(),
                            Source::Texture(t) => t.clone(),
                            Source::View(v) => v.texture().clone(),
                        };
                        objects.textures.insert(planned.id, (texture, shape));
                        // Every texture gets its whole view, so callbacks can always ask.
                        let mut keys = vec![ViewKey::Aspect(Aspect::All)];
                        match role {
                            TextureRole::Sampled { aspect } => keys.push(ViewKey::Aspect(aspect)),
                            _ if access.role.is_attachment() => keys.push(ViewKey::Attachment),
                            _ => {}
                        }
                        for key in keys {
                            let made = match key {
                                ViewKey::Aspect(aspect) => {
                                    objects.views.contains_key(&(planned.id, aspect))
                                }
                                ViewKey::Attachment => {
                                    objects.attachments.contains_key(&planned.id)
                                }
                            };
                            if made {
                                continue;
                            }
                            let view = self.view(source, key).map_err(|aspect| {
                                ImportError::ViewAspect {
                                    pass: pass.name.clone(),
                                    resource: planned.name.clone(),
                                    aspect,
                                }
                            })?;
                            match key {
                                ViewKey::Aspect(aspect) => {
                                    objects.views.insert((planned.id, aspect), view)
                                }
                                ViewKey::Attachment => objects.attachments.insert(planned.id, view),
                            };
                        }
                    }
                }
            }
        }
        Ok(objects)
    }

    /// The view `key` of a texture. A view bound by the engine serves every key except a
    /// single aspect: `Err` names that aspect.
    fn view(
        &mut self,
        source: Source<'_>,
        key: ViewKey,
    ) -> Result<wgpu::TextureView, &'static str> {
        match (source, key) {
            (Source::Pooled(i), _) => Ok(self.pool.view(i, key)),
            (Source::Texture(t), _) => Ok(make_view(t, key)),
            (Source::View(_), ViewKey::Aspect(Aspect::DepthOnly)) => Err("depth"),
            (Source::View(_), ViewKey::Aspect(Aspect::StencilOnly)) => Err("stencil"),
            (Source::View(v), _) => Ok(v.clone()),
        }
    }

    /// The timestamp slot of each planned pass, `None` for passes that are not timed.
    fn timing_slots(&mut self, plan: &Plan) -> Vec<Option<u32>> {
        let Some(timestamps) = &mut self.timestamps else {
            return vec![None; plan.passes.len()];
        };
        let inside_encoders = timestamps.inside_encoders;
        let timeable = |p: &PlannedPass| p.kind != PassKind::Transfer || inside_encoders;
        let wanted = plan.passes.iter().filter(|p| timeable(p)).count();
        let capacity = timestamps.reserve(&self.device, wanted) as u32;
        let mut next = 0;
        plan.passes
            .iter()
            .map(|p| {
                (timeable(p) && next < capacity).then(|| {
                    next += 1;
                    next - 1
                })
            })
            .collect()
    }

    /// Records each pass into its own command encoder, under its own error scopes, so a
    /// device error names the pass that caused it. Returns the command buffers (the last
    /// one resolves the timestamps) and each pass's CPU time and held bytes; nothing is
    /// submitted.
    fn record(
        &self,
        graph: &mut Graph,
        plan: &Plan,
        objects: &FrameObjects,
        slots: &[Option<u32>],
    ) -> Result<(Vec<wgpu::CommandBuffer>, Vec<RecordedPass>), ExecuteError> {
        let timestamps = self.timestamps.as_ref();
        let mut buffers = Vec::with_capacity(plan.passes.len() + 1);
        let mut recorded_passes = Vec::with_capacity(plan.passes.len());
        for (planned, &slot) in plan.passes.iter().zip(slots) {
            let start = Instant::now();
            let scopes = ErrorScopes::push(&self.device);
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some(&planned.name),
                });
            let node = &mut graph.passes[planned.id.index()];
            let failure = std::cell::RefCell::new(None);
            let held = std::cell::Cell::new(0);
            let resources = FrameResources {
                device: &self.device,
                queue: &self.queue,
                output_size: plan.output_size,
                objects,
                pass: &node.name,
                accesses: &node.accesses,
                dropped: &planned.dropped_reads,
                resources: &graph.resources,
                failure: &failure,
                held: &held,
                frame: self.frames - 1,
            };
            let recorded = record_pass(
                &mut encoder,
                planned,
                node.record.as_mut(),
                objects,
                &resources,
                timestamps.zip(slot),
            );
            // wgpu reports errors inside passes when the encoder finishes.
            let buffer = encoder.finish();
            let errors = scopes.pop();
            if let Some(loss) = self.lost() {
                let at = LostAt::Pass(planned.name.clone());
                return Err(ExecuteError::DeviceLost { at, loss });
            }
            recorded?;
            if let Some(why) = failure.into_inner() {
                return Err(ExecuteError::Pass {
                    pass: planned.name.clone(),
                    why,
                });
            }
            if let Some(message) = errors {
                return Err(ExecuteError::Device {
                    pass: Some(planned.name.clone()),
                    message,
                });
            }
            buffers.push(buffer);
            recorded_passes.push(RecordedPass {
                cpu_ns: start.elapsed().as_nanos() as u64,
                held_bytes: held.get(),
            });
        }
        if let Some(t) = timestamps {
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("rgraph timestamps"),
                });
            t.resolve(&mut encoder, slots.iter().flatten().count() as u32);
            buffers.push(encoder.finish());
        }
        Ok((buffers, recorded_passes))
    }

    /// Timings per pass from the CPU times and held bytes (per pass), the CPU time of the
    /// whole record and submit, and the timestamp ticks of the timed passes.
    fn report(
        &self,
        plan: &Plan,
        slots: &[Option<u32>],
        (recorded, record_submit_ns): (Vec<RecordedPass>, u64),
        stamps: &[(u64, u64)],
    ) -> FrameReport {
        let ns = |ticks: u64| self.timestamps.as_ref().map_or(0, |t| t.nanoseconds(ticks));
        let passes = plan
            .passes
            .iter()
            .zip(recorded)
            .zip(slots)
            .map(|((pass, recorded), slot)| PassTiming {
                name: pass.name.clone(),
                kind: pass.kind,
                gpu_ns: slot
                    .and_then(|s| stamps.get(s as usize))
                    .map(|&(begin, end)| ns(end.saturating_sub(begin))),
                cpu_ns: recorded.cpu_ns,
                held_bytes: recorded.held_bytes,
            })
            .collect();
        let begin = stamps.iter().map(|s| s.0).min();
        let end = stamps.iter().map(|s| s.1).max();
        let stats = self.pool.stats();
        FrameReport {
            passes,
            gpu_total_ns: begin.zip(end).map(|(b, e)| ns(e.saturating_sub(b))),
            textures_allocated: stats.frame_textures_allocated,
            buffers_allocated: stats.frame_buffers_allocated,
            record_submit_ns,
        }
    }

    /// Waits for the frame and reads the begin and end ticks of each timed pass.
    fn read_timestamps(&self, slots: &[Option<u32>]) -> Result<Vec<(u64, u64)>, ExecuteError> {
        let device_error = |e: super::readback::ReadbackError| ExecuteError::Device {
            pass: None,
            message: format!("reading the pass timestamps: {e}"),
        };
        match &self.timestamps {
            Some(t) => t
                .read(&self.device, slots.iter().flatten().count() as u32)
                .map_err(device_error),
            None => {
                self.device
                    .poll(wgpu::PollType::wait_indefinitely())
                    .map_err(|e| device_error(e.into()))?;
                Ok(Vec::new())
            }
        }
    }
}

/// The plan's index into its physical textures or buffers for an exported, graph-created
/// resource.
fn exported_physical(plan: &Plan, id: ResourceId) -> Option<usize> {
    let planned = plan.resources.get(id.index())?;
    (planned.exported && planned.origin == Origin::Transient)
        .then_some(planned.physical)
        .flatten()
}

/// Where a texture of this frame comes from.
#[derive(Copy, Clone)]
enum Source<'b> {
    Pooled(usize),
    Texture(&'b wgpu::Texture),
    View(&'b wgpu::TextureView),
}

impl FrameObjects {
    fn attachment(
        &self,
        pass: &PlannedPass,
        id: ResourceId,
    ) -> Result<&wgpu::TextureView, ExecuteError> {
        self.attachments.get(&id).ok_or_else(|| {
            ExecuteError::Inconsistent(format!(
                "pass \"{}\" attaches resource #{}, which it does not declare",
                pass.name, id.0
            ))
        })
    }
}

/// `16384x16384, 4 sample(s), 1 mip(s), rgba16float, 8192.0 MiB for mip 0`: what a failed
/// allocation asked for.
fn describe_shape(shape: &TextureShape) -> String {
    let layers = match shape.layers {
        1 => String::new(),
        n => format!(" x {n} layers"),
    };
    let bytes = u64::from(shape.width)
        * u64::from(shape.height)
        * u64::from(shape.layers)
        * u64::from(shape.samples)
        * texel_bytes(shape.format);
    format!(
        "{}x{}{layers}, {} sample(s), {} mip(s), {}, {:.1} MiB for mip 0",
        shape.width,
        shape.height,
        shape.samples,
        shape.mips,
        format_name(shape.format),
        bytes as f64 / f64::from(1u32 << 20)
    )
}

fn device_message(pass: Option<&str>, message: &str) -> String {
    match pass {
        Some(pass) => format!("pass \"{pass}\" failed on the device:\n{message}"),
        None => format!("device error while executing the frame:\n{message}"),
    }
}

/// Begins the planned pass in `encoder`, runs its callback and ends it.
fn record_pass(
    encoder: &mut wgpu::CommandEncoder,
    planned: &PlannedPass,
    record: Option<&mut Record>,
    objects: &FrameObjects,
    resources: &FrameResources<'_>,
    timed: Option<(&Timestamps, u32)>,
) -> Result<(), ExecuteError> {
    match planned.kind {
        PassKind::Render => {
            let color = planned
                .color
                .iter()
                .map(|c| {
                    Ok(Some(wgpu::RenderPassColorAttachment {
                        view: objects.attachment(planned, c.resource)?,
                        depth_slice: None,
                        resolve_target: c
                            .resolve_target
                            .map(|r| objects.attachment(planned, r))
                            .transpose()?,
                        ops: operations(&c.ops, |[r, g, b, a]| wgpu::Color { r, g, b, a }),
                    }))
                })
                .collect::<Result<Vec<_>, ExecuteError>>()?;
            let depth_stencil = match &planned.depth_stencil {
                Some(ds) => Some(wgpu::RenderPassDepthStencilAttachment {
                    view: objects.attachment(planned, ds.resource)?,
                    // None: the aspect is attached read-only.
                    depth_ops: ds.depth.as_ref().map(|o| operations(o, |v| v)),
                    stencil_ops: ds.stencil.as_ref().map(|o| operations(o, |v| v)),
                }),
                None => None,
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(&planned.name),
                color_attachments: &color,
                depth_stencil_attachment: depth_stencil,
                timestamp_writes: timed.map(|(t, s)| t.render_writes(s)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            // No callback: the pass is its load/store operations (a clear).
            if let Some(Record::Render(f)) = record {
                f(&mut RenderContext {
                    pass: &mut pass,
                    resources,
                });
            }
        }
        PassKind::Compute => {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(&planned.name),
                timestamp_writes: timed.map(|(t, s)| t.compute_writes(s)),
            });
            if let Some(Record::Compute(f)) = record {
                f(&mut ComputeContext {
                    pass: &mut pass,
                    resources,
                });
            }
        }
        PassKind::Transfer => {
            if let Some((t, s)) = timed {
                t.write(encoder, s, false);
            }
            if let Some(Record::Transfer(f)) = record {
                f(&mut TransferContext { encoder, resources });
            }
            if let Some((t, s)) = timed {
                t.write(encoder, s, true);
            }
        }
    }
    Ok(())
}

fn operations<T: Copy, V>(ops: &Ops<T>, value: impl Fn(T) -> V) -> wgpu::Operations<V> {
    wgpu::Operations {
        load: match ops.load {
            Load::Clear(v) => wgpu::LoadOp::Clear(value(v)),
            // What the pass leaves undrawn is never read: a load costs nothing, where a
            // clear costs a full-screen pass's writes (wgpu initialises the memory once).
            Load::Load | Load::Overwrite => wgpu::LoadOp::Load,
        },
        store: match ops.store {
            Store::Store => wgpu::StoreOp::Store,
            Store::Discard => wgpu::StoreOp::Discard,
        },
    }
}

/// Each pass's callback must record the kind of commands the pass begins.
fn check_records(graph: &Graph, plan: &Plan) -> Result<(), ExecuteError> {
    for planned in &plan.passes {
        let node = &graph.passes[planned.id.index()];
        if let Some(record) = &node.record {
            if record.kind() != node.kind {
                return Err(ExecuteError::RecordKind {
                    pass: node.name.clone(),
                    kind: node.kind,
                    record: record.kind(),
                });
            }
        }
    }
    Ok(())
}
