//! The device objects of a pass that reads G-buffer textures (light, tiled light,
//! G-buffer resolve, full-screen passes): its shader module, the bind group layout of its inputs, a
//! pipeline layout of the scene's group 0 (when it reads the scene), the inputs' group
//! 1 and, for a visibility buffer's shading, the scene's geometry as group 2 and a
//! compute rasteriser's keys as group 3; and its pipelines. Built on the first frame of a device or scene upload, kept after.

use graph_core::gpu::FrameResources;

use super::bindings::TextureBindings;
use super::pipeline::{module, pipeline_layout, Pipelines};
use crate::common::textures::Input;
use crate::gpu_scene::GpuScene;

pub(crate) struct InputPass<K, P = wgpu::RenderPipeline> {
    pub module: wgpu::ShaderModule,
    pub inputs: TextureBindings,
    pub layout: wgpu::PipelineLayout,
    pub pipelines: Pipelines<K, P>,
    /// What it reads of a visibility buffer besides its textures.
    pub geometry: Geometry,
    /// Group 3 with [`Geometry::TrianglesAndKeys`]: a compute rasteriser's keys.
    keys: Option<wgpu::BindGroupLayout>,
}

/// What a pass shading a visibility buffer binds besides its textures.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Geometry {
    /// Nothing: it reads a G-buffer.
    None,
    /// The scene's geometry as group 2 ([`GpuScene::geometry_layout`]), to rebuild a
    /// raster pass's triangle IDs.
    Triangles,
    /// That, and a compute rasteriser's keys (common/visibility_samples.rs) as group 3.
    TrianglesAndKeys,
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
        Self::with_geometry(resources, label, source, scene, inputs, Geometry::None)
    }

    /// As [`new`](Self::new), and with what `geometry` says as groups 2 and 3.
    pub fn with_geometry(
        resources: &FrameResources<'_>,
        label: &str,
        source: &str,
        scene: Option<&GpuScene>,
        inputs: &[Input],
        geometry: Geometry,
    ) -> Self {
        let device = resources.device;
        let inputs = TextureBindings::new(resources, inputs);
        let keys = (geometry == Geometry::TrianglesAndKeys).then(|| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("visibility keys"),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            })
        });
        let triangles = scene
            .filter(|_| geometry != Geometry::None)
            .map(GpuScene::geometry_layout);
        let layouts = [
            scene.map(GpuScene::layout),
            Some(&inputs.layout),
            triangles,
            keys.as_ref(),
        ];
        let used = layouts.iter().rposition(Option::is_some).map_or(0, |last| last + 1);
        InputPass {
            module: module(device, label, source),
            layout: pipeline_layout(device, &layouts[..used]),
            inputs,
            pipelines: Pipelines::default(),
            geometry,
            keys,
        }
    }

    /// Group 3 for this frame's keys `buffer` (a pool may lend another buffer each
    /// frame); `None` unless made with [`Geometry::TrianglesAndKeys`].
    pub fn keys_group(
        &self,
        resources: &FrameResources<'_>,
        buffer: &wgpu::Buffer,
    ) -> Option<wgpu::BindGroup> {
        let layout = self.keys.as_ref()?;
        Some(resources.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("visibility keys"),
            layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        }))
    }
}
