//! The device objects of a pass that reads G-buffer textures (light, tiled light,
//! G-buffer resolve, full-screen passes): its shader module, the bind group layout of its inputs, a
//! pipeline layout of the scene's group 0 (when it reads the scene), the inputs' group
//! 1 (storage buffers among them: a compute rasteriser's visibility buffer) and, for a
//! visibility buffer's shading, the scene's geometry as group 2 and its texture table as
//! group 3; and its pipelines. Built on the first frame of a device or scene upload, kept
//! after.

use rgraph_core::gpu::FrameResources;
use rgraph_core::BufferHandle;

use super::bindings::TextureBindings;
use super::pipeline::{module, pipeline_layout, Pipelines};
use crate::common::textures::Input;
use crate::gpu_scene::GpuScene;

/// The storage buffers of a pass's group 1: graph buffers it reads, by binding, and the
/// bindings of read-write buffers it owns (bound with `TextureBindings::bind_group_with`).
#[derive(Default)]
pub(crate) struct GroupBuffers {
    pub read: Vec<(u32, BufferHandle)>,
    pub owned: Vec<u32>,
}

pub(crate) struct InputPass<K, P = wgpu::RenderPipeline> {
    pub module: wgpu::ShaderModule,
    pub inputs: TextureBindings,
    pub layout: wgpu::PipelineLayout,
    pub pipelines: Pipelines<K, P>,
}

impl<K, P> InputPass<K, P> {
    /// For `source`'s shader reading `inputs` as the plan shapes them, and `scene`'s
    /// group 0 when given.
    pub fn new(
        resources: &FrameResources<'_>,
        label: &str,
        source: &str,
        scene: Option<&GpuScene>,
        inputs: &[Input],
    ) -> Self {
        Self::with_geometry(
            resources,
            label,
            source,
            scene,
            inputs,
            &GroupBuffers::default(),
            false,
        )
    }

    /// As [`new`](Self::new), with the storage `buffers` in group 1 (at their bindings),
    /// and with `geometry` the scene's geometry as group 2
    /// ([`GpuScene::geometry_layout`]) and its texture table as group 3
    /// ([`GpuScene::texture_table_layout`]).
    pub fn with_geometry(
        resources: &FrameResources<'_>,
        label: &str,
        source: &str,
        scene: Option<&GpuScene>,
        inputs: &[Input],
        buffers: &GroupBuffers,
        geometry: bool,
    ) -> Self {
        let device = resources.device;
        let inputs =
            TextureBindings::with_buffers(resources, inputs, &buffers.read, &buffers.owned);
        let visibility = scene.filter(|_| geometry);
        let layouts = [
            scene.map(GpuScene::layout),
            Some(&inputs.layout),
            visibility.map(GpuScene::geometry_layout),
            visibility.map(GpuScene::texture_table_layout),
        ];
        InputPass {
            module: module(device, label, source),
            layout: pipeline_layout(
                device,
                &layouts[..2 + 2 * usize::from(visibility.is_some())],
            ),
            inputs,
            pipelines: Pipelines::default(),
        }
    }
}
