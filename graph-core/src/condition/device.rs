//! Device conditions: what a device is or has, which graph conditions test by name as they
//! test a scene's features. The device sets them (through its profile), never the caller.

use wgpu_types::Features;

/// What a device condition stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeviceTrait {
    /// Optional device features, all of them.
    Features(Features),
    /// The adapter is the CPU (`DeviceType::Cpu`: lavapipe, llvmpipe, WARP), where work a
    /// GPU's fixed-function units do (rasterisation) is emulated in shader code and may
    /// cost more than the same work written as a compute shader costs on a GPU, or less.
    Cpu,
    /// The device allows at least this many bytes per sample of a render pass's color
    /// attachments (`max_color_attachment_bytes_per_sample`, as WebGPU counts them; every
    /// device allows 32).
    ColorBytesPerSample(u32),
}

/// The device conditions and what each stands for: a file declaring `int64_atomics` in its
/// `features` can pick a pass that needs 64-bit atomics on devices that have them and
/// another elsewhere; one declaring `cpu_device` picks a pass for CPU adapters; one
/// declaring `color_bytes_64` gives a render pass more color targets than WebGPU's 32
/// bytes per sample hold where the device allows 64 (desktop GPUs do: Vulkan adapters
/// report 128).
pub const DEVICE_CONDITIONS: [(&str, DeviceTrait); 3] = [
    (
        "int64_atomics",
        DeviceTrait::Features(Features::SHADER_INT64.union(Features::SHADER_INT64_ATOMIC_MIN_MAX)),
    ),
    ("cpu_device", DeviceTrait::Cpu),
    ("color_bytes_64", DeviceTrait::ColorBytesPerSample(64)),
];

/// Whether `name` is one of [`DEVICE_CONDITIONS`].
pub fn is_device_condition(name: &str) -> bool {
    DEVICE_CONDITIONS.iter().any(|(n, _)| *n == name)
}
