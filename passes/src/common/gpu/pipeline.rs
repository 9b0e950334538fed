//! Building render pipelines from the deferred shaders (shader modules, pipeline layouts,
//! the pipelines), and keeping pipelines (render or compute). Every object is created
//! through [`crate::kept`], which returns the one built before on the device for the same
//! description, whatever graph built it.

pub(crate) use crate::kept::{module, pipeline_layout};

/// Everything that varies between the deferred passes' pipelines.
pub(crate) struct PipelineDesc<'a> {
    pub label: &'a str,
    pub layout: &'a wgpu::PipelineLayout,
    pub module: &'a wgpu::ShaderModule,
    pub vertex: &'a str,
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub fragment: &'a str,
    /// Pipeline-overridable constants, given to both stages.
    pub constants: &'a [(&'a str, f64)],
    pub targets: &'a [Option<wgpu::ColorTargetState>],
    pub cull: Option<wgpu::Face>,
    pub depth_stencil: Option<wgpu::DepthStencilState>,
    pub samples: u32,
    /// Which samples the pipeline may write (`!0` for all).
    pub mask: u64,
}

impl PipelineDesc<'_> {
    /// The pipeline, drawing triangle lists.
    pub fn build(&self, device: &wgpu::Device) -> wgpu::RenderPipeline {
        self.build_as(device, wgpu::PrimitiveTopology::TriangleList)
    }

    /// The pipeline, drawing `topology` (the points and lines pass draws line lists).
    pub fn build_as(
        &self,
        device: &wgpu::Device,
        topology: wgpu::PrimitiveTopology,
    ) -> wgpu::RenderPipeline {
        let options = wgpu::PipelineCompilationOptions {
            constants: self.constants,
            zero_initialize_workgroup_memory: false,
        };
        let descriptor = wgpu::RenderPipelineDescriptor {
            label: Some(self.label),
            layout: Some(self.layout),
            vertex: wgpu::VertexState {
                module: self.module,
                entry_point: Some(self.vertex),
                compilation_options: options.clone(),
                buffers: self.buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology,
                cull_mode: self.cull,
                ..Default::default()
            },
            depth_stencil: self.depth_stencil.clone(),
            multisample: wgpu::MultisampleState {
                count: self.samples,
                mask: self.mask,
                alpha_to_coverage_enabled: false,
            },
            fragment: Some(wgpu::FragmentState {
                module: self.module,
                entry_point: Some(self.fragment),
                compilation_options: options,
                targets: self.targets,
            }),
            multiview_mask: None,
            cache: None,
        };
        crate::kept::render_pipeline(device, &descriptor)
    }
}

/// The compute pipeline of `module`'s `entry` with pipeline-overridable `constants`.
/// Workgroup memory is not zero-initialised: the deferred compute shaders initialise what
/// they read of it (or have none), and the driver's clear would cost every workgroup.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    let descriptor = wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        module,
        entry_point: Some(entry),
        compilation_options: wgpu::PipelineCompilationOptions {
            constants,
            zero_initialize_workgroup_memory: false,
        },
        cache: None,
    };
    crate::kept::compute_pipeline(device, &descriptor)
}

/// Adds color and alpha: how light contributions accumulate in the HDR target.
pub(crate) fn additive(format: wgpu::TextureFormat) -> wgpu::ColorTargetState {
    let add = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    wgpu::ColorTargetState {
        format,
        blend: Some(wgpu::BlendState {
            color: add,
            alpha: add,
        }),
        write_mask: wgpu::ColorWrites::ALL,
    }
}

/// Pipelines made on first use, by key. Keys hold what the plan decides (formats, sample
/// counts) and the pass's own variants; plans rarely change, so a list is enough.
pub(crate) struct Pipelines<K, P = wgpu::RenderPipeline> {
    built: Vec<(K, P)>,
}

impl<K, P> Default for Pipelines<K, P> {
    fn default() -> Self {
        Pipelines { built: Vec::new() }
    }
}

impl<K: PartialEq, P> Pipelines<K, P> {
    pub fn get(&mut self, key: K, build: impl FnOnce(&K) -> P) -> &P {
        let index = match self.built.iter().position(|(k, _)| *k == key) {
            Some(index) => index,
            None => {
                let pipeline = build(&key);
                self.built.push((key, pipeline));
                self.built.len() - 1
            }
        };
        &self.built[index].1
    }
}
