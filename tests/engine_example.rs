//! The engine example (examples/engine_integration.rs, compiled into this binary) run as
//! a test: an animated sequence through one executor whose frames after the first
//! allocate nothing and create no device object, while the image does change.

use rgraph_core::gpu::DeviceObjects;

use crate::deferred_support::gpu;
use crate::engine_integration::{animate, FrameStats, SIZE};

#[test]
fn frames_after_the_first_allocate_nothing_and_create_no_pipelines() {
    let gpu = gpu();
    let mut images = Vec::new();
    for frames in [1, 4] {
        let mut stats: Vec<FrameStats> = Vec::new();
        let image =
            animate(&gpu, frames, SIZE, |_, frame| stats.push(*frame)).expect("the example runs");
        let first = &stats[0];
        // Pipelines are kept per device for every graph on it (rgraph-passes' kept.rs):
        // the second run, or an earlier test's on this device, may have built them all.
        // The scene's buffers are the graph's own.
        assert!(
            first.created.buffers > 0 && first.textures_allocated > 0,
            "the first frame uploads the scene and allocates the targets (counted: {}); \
             is wgpu's counters feature off?",
            first.created
        );
        for (index, frame) in stats.iter().enumerate().skip(1) {
            assert_eq!(
                (frame.textures_allocated, frame.buffers_allocated),
                (0, 0),
                "frame {index} allocated graph resources"
            );
            assert_eq!(
                frame.created,
                DeviceObjects::default(),
                "frame {index} created device objects"
            );
        }
        images.push(image);
    }
    assert_ne!(
        images[0], images[1],
        "the animation did not change the image"
    );
}
