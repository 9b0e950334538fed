//! Device conditions: optional device features graph conditions test by name, as they
//! test a scene's features. The device sets them (through its profile), never the caller.

use wgpu_types::Features;

/// The device conditions and the device features each stands for: a file declaring
/// `int64_atomics` in its `features` can pick a pass that needs 64-bit atomics on devices
/// that have them and another elsewhere.
pub const DEVICE_CONDITIONS: [(&str, Features); 1] = [(
    "int64_atomics",
    Features::SHADER_INT64.union(Features::SHADER_INT64_ATOMIC_MIN_MAX),
)];

/// Whether `name` is one of [`DEVICE_CONDITIONS`].
pub fn is_device_condition(name: &str) -> bool {
    DEVICE_CONDITIONS.iter().any(|(n, _)| *n == name)
}
