//! A GPU that fails cleanly. An allocation a pass's callback makes beyond what the device
//! can hold fails the frame naming the pass and the object's label. A device lost in the middle of a frame fails that frame with
//! an error naming the loss and the frame's passes (wgpu reports a destroyed device only
//! once the frame is waited for, so which of them was running is not known), every later
//! frame on it fails at once naming the loss (no work, and none of the device errors that
//! follow from it), and the same compiled graph runs again on a new device through a new executor, in the same process:
//! what an engine does after a GPU reset or a shader timeout. lavapipe cannot reset or time
//! out, so `Device::destroy` stands in for the loss (wgpu reports it through the same
//! device-lost callback, reason `Destroyed` instead of `Unknown`).

use rgraph_core::gpu::{read_texture, ExecuteError, Executor, Imports, LostAt};
use rgraph_core::{ColorLoad, GraphBuilder, Size, TextureDesc};
use wgpu::TextureFormat;

use crate::common::{compile, gpu, SIZE};
use crate::deferred_support::Render;

#[test]
fn a_device_destroyed_mid_frame_fails_naming_the_loss_and_a_new_device_runs_the_graph() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let desc = TextureDesc::new(TextureFormat::Rgba8Unorm).size(Size::Absolute(SIZE.0, SIZE.1));
    let target = g.create_texture("target", desc);
    let mut pass = g.add_render_pass("draw");
    let out = pass.color_output(target, ColorLoad::Clear([1.0, 0.0, 0.0, 1.0]));
    // The second frame destroys the device it is recorded on, in the middle of the pass.
    let mut frames = 0;
    pass.render(move |ctx| {
        frames += 1;
        if frames == 2 {
            ctx.resources.device.destroy();
        }
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let mut executor = Executor::new(&gpu);
    executor
        .execute(&mut compiled, &Imports::new())
        .expect("the first frame runs");

    let error = executor
        .execute(&mut compiled, &Imports::new())
        .expect_err("the device is destroyed during the frame");
    assert!(
        matches!(&error, ExecuteError::DeviceLost { at: LostAt::Frame(passes), loss }
            if passes == &["draw"] && loss.reason == wgpu::DeviceLostReason::Destroyed),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        "the device was lost while the frame ran (its passes: \"draw\"): it was destroyed; \
         open a new device and run the graph with a new Executor on it"
    );
    let error = executor
        .execute(&mut compiled, &Imports::new())
        .expect_err("the device stays lost");
    assert!(
        matches!(
            &error,
            ExecuteError::DeviceLost {
                at: LostAt::Start,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        error
            .to_string()
            .starts_with("the device was lost before the frame began: it was destroyed"),
        "{error}"
    );
    assert!(
        gpu.take_errors().is_empty(),
        "errors after the loss were reported"
    );

    // The engine's recovery: a new device, a new executor, the same compiled graph.
    let again = crate::common::gpu();
    let mut executor = Executor::new(&again);
    executor
        .execute(&mut compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("the graph runs on the new device: {e}"));
    let texture = executor
        .texture(compiled.plan(), out.id())
        .expect("the target is exported");
    let bytes = read_texture(&again.device, &again.queue, texture).expect("readback");
    assert_eq!(&bytes[..4], &[255, 0, 0, 255]);
    assert!(bytes.chunks_exact(4).all(|t| t == [255, 0, 0, 255]));
}

/// The deferred plugins keep pipelines and the scene's upload per device: on a new device
/// after a loss they build them again, and the frame is the one the lost device drew.
#[test]
fn a_deferred_pipeline_draws_the_same_frame_on_a_new_device_after_a_loss() {
    let gpu = gpu();
    let render = Render::new("deferred_msaa_4x.ron", "builtin:spheres", (64, 48));
    let mut frame = render.run(&gpu);
    let before = frame.image(&gpu, "color");
    gpu.device.destroy();
    let error = frame.try_again().expect_err("the device is destroyed");
    assert!(
        matches!(&error, ExecuteError::DeviceLost { .. }),
        "{error:?}"
    );

    let again = crate::common::gpu();
    frame.move_to(&again);
    frame
        .try_again()
        .unwrap_or_else(|e| panic!("the graph runs on the new device: {e}"));
    let after = frame.image(&again, "color");
    assert!(
        before.pixels.iter().any(|p| p[..3] != [0, 0, 0]),
        "the frame drew nothing"
    );
    let differing = (before.pixels.iter().zip(&after.pixels))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "the new device's frame differs in {differing} pixels"
    );
}

/// A buffer a pass creates for itself beyond the device's largest (a stand-in for running
/// out of memory, which lavapipe would rather satisfy) fails the frame naming the pass and
/// the buffer's label, and nothing is submitted.
#[test]
fn an_allocation_a_pass_makes_beyond_the_device_names_the_pass_and_the_object() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let desc = TextureDesc::new(TextureFormat::Rgba8Unorm).size(Size::Absolute(SIZE.0, SIZE.1));
    let target = g.create_texture("target", desc);
    let mut pass = g.add_render_pass("lights");
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    let too_big = gpu.device.limits().max_buffer_size + 4;
    pass.render(move |ctx| {
        let _failed = ctx.resources.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("light list"),
            size: too_big,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let error = Executor::new(&gpu)
        .execute(&mut compiled, &Imports::new())
        .expect_err("the buffer is beyond the device");
    assert!(
        matches!(&error, ExecuteError::Device { pass: Some(p), .. } if p == "lights"),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.starts_with("pass \"lights\" failed on the device:"),
        "{message}"
    );
    assert!(message.contains("light list"), "{message}");
}
