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
}

/// The device conditions and what each stands for: a file declaring `int64_atomics` in its
/// `features` can pick a pass that needs 64-bit atomics on devices that have them and
/// another elsewhere; one declaring `cpu_device` picks a pass for CPU adapters.
pub const DEVICE_CONDITIONS: [(&str, DeviceTrait); 2] = [
    (
        "int64_atomics",
        DeviceTrait::Features(Features::SHADER_INT64.union(Features::SHADER_INT64_ATOMIC_MIN_MAX)),
    ),
    ("cpu_device", DeviceTrait::Cpu),
];

/// Whether `name` is one of [`DEVICE_CONDITIONS`].
pub fn is_device_condition(name: &str) -> bool {
    DEVICE_CONDITIONS.iter().any(|(n, _)| *n == name)
}
