//! Device objects kept by their full description, for every graph a process records on a
//! device: bind group layouts, pipeline layouts, shader modules, render and compute
//! pipelines.
//!
//! A pass builds its objects on its first frame of a device and keeps them for its graph
//! (`common/gpu/recorder.rs`); a second graph on the same device (a reloaded file, another
//! view, the next render of a test) builds them again. On lavapipe that is what a frame
//! costs: creating one `light_tiled` pipeline takes 0.5 to 0.9 s of Mesa's shader
//! compiler (its NIR passes run at every creation; only the LLVM code is found in Mesa's
//! on-disk cache), against milliseconds of drawing at test sizes. So every pass creates
//! these objects through this module, which returns the object built before for the same
//! description on the same device.
//!
//! # Contract
//!
//! - **Owner.** The process: one store per device, behind a lock, shared by every graph
//!   and thread. A device keeps its objects while it is among the [`DEVICES`] devices
//!   used last; the next device after those drops the objects of the one used least
//!   recently (and with them the store's hold on that device). Of each kind of object a
//!   device keeps the [`OBJECTS`] used last. Callers get clones of the handles, which
//!   stay valid however long they keep them; a dropped object is built again when next
//!   asked for.
//! - **Keys.** A key holds everything the object is built from: the label, the entries
//!   of a bind group layout, the WGSL after composition, entry points, overridable
//!   constants (by their bits), vertex buffers, targets, formats, topology, cull mode,
//!   depth-stencil state, sample count and mask. Objects a key refers to (a pipeline's
//!   layout and module, a layout's groups) are compared by identity: the key holds a
//!   clone of each, so no other object can take its identity while the key lives. Built
//!   through this module, equal descriptions give identical objects, so a pipeline found
//!   here is found whatever graph asks for it.
//! - **Invalidation.** None: an object is a function of its key. An object whose creation
//!   failed (wgpu reports the error in the scope it was created in) is kept too: later
//!   frames that use it fail with wgpu's error for an invalid object.
//! - **Device objects.** Kept objects stay alive after the graphs that made them are
//!   dropped, so a device's live-object counts (`DeviceObjects::alive`) include them; a
//!   frame still creates nothing after its graph's first (what the soak and frame-input
//!   tests check), and a graph's first frame creates only what no earlier graph made.

use std::collections::HashMap;
use std::hash::Hash;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// How many devices keep their objects at once: the devices a process uses at one time
/// (a test process opens one per test thread, the viewer one, and one more after a
/// device loss).
pub(crate) const DEVICES: usize = 8;

/// How many objects of each kind (bind group layouts, pipeline layouts, modules, render
/// and compute pipelines) a device keeps: the ones used last, which bounds what a process
/// that builds ever new variants holds (a test process builds hundreds).
pub(crate) const OBJECTS: usize = 128;

/// One device's objects, by key.
#[derive(Default)]
struct Kept {
    group_layouts: Recent<GroupLayoutKey, wgpu::BindGroupLayout>,
    pipeline_layouts: Recent<PipelineLayoutKey, wgpu::PipelineLayout>,
    modules: Recent<ModuleKey, wgpu::ShaderModule>,
    render: Recent<RenderKey, wgpu::RenderPipeline>,
    compute: Recent<ComputeKey, wgpu::ComputePipeline>,
}

/// Objects of one kind by key, each with the number of its last use; past [`OBJECTS`],
/// the least recently used is dropped.
struct Recent<K, V> {
    uses: u64,
    objects: HashMap<K, (V, u64)>,
}

impl<K, V> Default for Recent<K, V> {
    fn default() -> Self {
        Recent {
            uses: 0,
            objects: HashMap::new(),
        }
    }
}

impl<K: Hash + Eq, V: Clone> Recent<K, V> {
    fn find_or_build(&mut self, key: K, build: impl FnOnce() -> V) -> V {
        self.uses += 1;
        let now = self.uses;
        if let Some((object, used)) = self.objects.get_mut(&key) {
            *used = now;
            return object.clone();
        }
        if self.objects.len() >= OBJECTS {
            let oldest = self.objects.values().map(|&(_, used)| used).min();
            self.objects.retain(|_, (_, used)| Some(*used) != oldest);
        }
        let object = build();
        self.objects.insert(key, (object.clone(), now));
        object
    }
}

/// The devices with objects kept, each with the number of its last use.
#[derive(Default)]
struct Devices {
    uses: u64,
    kept: Vec<(wgpu::Device, u64, Arc<Mutex<Kept>>)>,
}

/// A lock that a panic while holding it (a build that panicked) leaves usable: the maps
/// it guards are never left half-updated.
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

/// `device`'s objects, made the most recently used.
fn kept(device: &wgpu::Device) -> Arc<Mutex<Kept>> {
    static DEVICES_KEPT: Mutex<Devices> = Mutex::new(Devices {
        uses: 0,
        kept: Vec::new(),
    });
    let mut devices = lock(&DEVICES_KEPT);
    devices.uses += 1;
    let now = devices.uses;
    if let Some((_, used, kept)) = devices.kept.iter_mut().find(|(d, ..)| d == device) {
        *used = now;
        return kept.clone();
    }
    if devices.kept.len() == DEVICES {
        let oldest = (devices.kept.iter().enumerate())
            .min_by_key(|(_, (_, used, _))| *used)
            .map(|(index, _)| index)
            .expect("DEVICES is not zero");
        devices.kept.swap_remove(oldest);
    }
    let kept = Arc::new(Mutex::new(Kept::default()));
    devices.kept.push((device.clone(), now, kept.clone()));
    kept
}

/// The object `map` of `device`'s store holds for `key`, built by `build` when none does.
/// The device's store stays locked while `build` runs: builds on one device take turns,
/// and `build` must not come back here.
fn find_or_build<K: Hash + Eq, V: Clone>(
    device: &wgpu::Device,
    map: fn(&mut Kept) -> &mut Recent<K, V>,
    key: K,
    build: impl FnOnce() -> V,
) -> V {
    let kept = kept(device);
    let mut kept = lock(&kept);
    map(&mut kept).find_or_build(key, build)
}

#[derive(PartialEq, Eq, Hash)]
struct GroupLayoutKey {
    label: String,
    entries: Vec<wgpu::BindGroupLayoutEntry>,
}

/// A layout entry for a buffer of kind `ty` at `binding`, seen by `visibility`, with no
/// dynamic offset or least size: what the scene's and the passes' own groups of whole
/// buffers are made of.
pub(crate) fn buffer_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BufferBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The bind group layout of `entries`.
pub(crate) fn bind_group_layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> wgpu::BindGroupLayout {
    let key = GroupLayoutKey {
        label: label.to_owned(),
        entries: entries.to_vec(),
    };
    find_or_build(
        device,
        |k| &mut k.group_layouts,
        key,
        || {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        },
    )
}

#[derive(PartialEq, Eq, Hash)]
struct PipelineLayoutKey {
    groups: Vec<Option<wgpu::BindGroupLayout>>,
}

/// A pipeline layout of `groups` in order; `None` leaves a group unused.
pub(crate) fn pipeline_layout(
    device: &wgpu::Device,
    groups: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::PipelineLayout {
    let key = PipelineLayoutKey {
        groups: groups.iter().map(|g| g.cloned()).collect(),
    };
    find_or_build(
        device,
        |k| &mut k.pipeline_layouts,
        key,
        || {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: None,
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        },
    )
}

#[derive(PartialEq, Eq, Hash)]
struct ModuleKey {
    label: String,
    wgsl: String,
}

/// The shader module of `wgsl` (composed: the text wgpu compiles).
pub(crate) fn module(device: &wgpu::Device, label: &str, wgsl: &str) -> wgpu::ShaderModule {
    let key = ModuleKey {
        label: label.to_owned(),
        wgsl: wgsl.to_owned(),
    };
    find_or_build(
        device,
        |k| &mut k.modules,
        key,
        || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            })
        },
    )
}

/// A stage's compilation options: pipeline-overridable constants by name and the bits of
/// their value (0.0 and -0.0, or two NaNs, are different keys, which only costs a second
/// build), and whether workgroup memory is zeroed.
#[derive(PartialEq, Eq, Hash)]
struct OptionsKey {
    constants: Vec<(String, u64)>,
    zero_initialize_workgroup_memory: bool,
}

impl OptionsKey {
    fn of(options: &wgpu::PipelineCompilationOptions<'_>) -> Self {
        OptionsKey {
            constants: (options.constants.iter())
                .map(|&(name, value)| (name.to_owned(), value.to_bits()))
                .collect(),
            zero_initialize_workgroup_memory: options.zero_initialize_workgroup_memory,
        }
    }
}

/// A stage: its module, entry point and options.
#[derive(PartialEq, Eq, Hash)]
struct StageKey {
    module: wgpu::ShaderModule,
    entry: Option<String>,
    options: OptionsKey,
}

impl StageKey {
    fn of(
        module: &wgpu::ShaderModule,
        entry: Option<&str>,
        options: &wgpu::PipelineCompilationOptions<'_>,
    ) -> Self {
        StageKey {
            module: module.clone(),
            entry: entry.map(str::to_owned),
            options: OptionsKey::of(options),
        }
    }
}

/// A vertex buffer layout that owns its attributes.
#[derive(PartialEq, Eq, Hash)]
struct VertexBufferKey {
    array_stride: wgpu::BufferAddress,
    step_mode: wgpu::VertexStepMode,
    attributes: Vec<wgpu::VertexAttribute>,
}

/// Everything a render pipeline is built from (see [`render_pipeline`]).
#[derive(PartialEq, Eq, Hash)]
struct RenderKey {
    label: Option<String>,
    layout: Option<wgpu::PipelineLayout>,
    vertex: StageKey,
    buffers: Vec<Option<VertexBufferKey>>,
    fragment: Option<(StageKey, Vec<Option<wgpu::ColorTargetState>>)>,
    primitive: wgpu::PrimitiveState,
    depth_stencil: Option<wgpu::DepthStencilState>,
    multisample: wgpu::MultisampleState,
}

/// The render pipeline of `descriptor`, which has no multiview mask or driver cache (it
/// panics here otherwise: no pass sets them).
pub(crate) fn render_pipeline(
    device: &wgpu::Device,
    descriptor: &wgpu::RenderPipelineDescriptor<'_>,
) -> wgpu::RenderPipeline {
    assert!(
        descriptor.multiview_mask.is_none() && descriptor.cache.is_none(),
        "kept pipelines have no multiview mask or driver cache"
    );
    let vertex = &descriptor.vertex;
    let key = RenderKey {
        label: descriptor.label.map(str::to_owned),
        layout: descriptor.layout.cloned(),
        vertex: StageKey::of(
            vertex.module,
            vertex.entry_point,
            &vertex.compilation_options,
        ),
        buffers: (vertex.buffers.iter())
            .map(|buffer| {
                buffer.as_ref().map(|b| VertexBufferKey {
                    array_stride: b.array_stride,
                    step_mode: b.step_mode,
                    attributes: b.attributes.to_vec(),
                })
            })
            .collect(),
        fragment: descriptor.fragment.as_ref().map(|f| {
            let stage = StageKey::of(f.module, f.entry_point, &f.compilation_options);
            (stage, f.targets.to_vec())
        }),
        primitive: descriptor.primitive,
        depth_stencil: descriptor.depth_stencil.clone(),
        multisample: descriptor.multisample,
    };
    find_or_build(
        device,
        |k| &mut k.render,
        key,
        || device.create_render_pipeline(descriptor),
    )
}

/// Everything a compute pipeline is built from (see [`compute_pipeline`]).
#[derive(PartialEq, Eq, Hash)]
struct ComputeKey {
    label: Option<String>,
    layout: Option<wgpu::PipelineLayout>,
    stage: StageKey,
}

/// The compute pipeline of `descriptor`, which has no driver cache (it panics here
/// otherwise: no pass sets one). With `layout: None` its layout is derived from the
/// shader, and bind groups must be made for `get_bind_group_layout` of the pipeline
/// returned.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    descriptor: &wgpu::ComputePipelineDescriptor<'_>,
) -> wgpu::ComputePipeline {
    assert!(
        descriptor.cache.is_none(),
        "kept pipelines have no driver cache"
    );
    let key = ComputeKey {
        label: descriptor.label.map(str::to_owned),
        layout: descriptor.layout.cloned(),
        stage: StageKey::of(
            descriptor.module,
            descriptor.entry_point,
            &descriptor.compilation_options,
        ),
    };
    find_or_build(
        device,
        |k| &mut k.compute,
        key,
        || device.create_compute_pipeline(descriptor),
    )
}
