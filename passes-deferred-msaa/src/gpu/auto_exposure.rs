//! Recording the auto-exposure pass: one workgroup meters the image; its pipeline is made
//! on the first frame of a device and kept.

use graph_core::gpu::ComputeContext;

use crate::common::gpu::InputPass;
use crate::passes::auto_exposure::Metering;

pub(crate) fn record(metering: Metering) -> Box<dyn FnMut(&mut ComputeContext<'_, '_>)> {
    let mut state: Option<(wgpu::Device, InputPass<(), wgpu::ComputePipeline>)> = None;
    Box::new(move |ctx| {
        let resources = ctx.resources;
        let device = resources.device;
        if state.as_ref().is_some_and(|(built, _)| built != device) {
            state = None;
        }
        let (_, state) = state.get_or_insert_with(|| {
            let pass = InputPass::new(
                resources,
                "auto_exposure",
                &metering.source,
                None,
                &metering.inputs,
            );
            (device.clone(), pass)
        });
        let (module, layout) = (&state.module, &state.layout);
        let pipeline = state.pipelines.get((), |()| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("auto_exposure"),
                layout: Some(layout),
                module,
                entry_point: Some("cs_auto_exposure"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &metering.constants,
                    // The shader clears its histogram itself.
                    zero_initialize_workgroup_memory: false,
                },
                cache: None,
            })
        });
        ctx.pass.set_pipeline(pipeline);
        ctx.pass
            .set_bind_group(1, &state.inputs.bind_group(resources), &[]);
        ctx.pass.dispatch_workgroups(1, 1, 1);
    })
}
