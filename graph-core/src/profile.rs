//! Device profiles: the limits and format capabilities a graph is validated against, as
//! plain data. A profile can come from the WebGPU defaults, a real adapter, or a file an
//! engine recorded from its target hardware, so CI validates without the GPU.

use serde::{Deserialize, Serialize};
use wgpu_types::{
    Features, Limits, TextureFormat, TextureFormatFeatureFlags, TextureFormatFeatures,
    TextureUsages,
};

use crate::condition::{self, DeviceTrait, DEVICE_CONDITIONS};

/// What a device can do, as far as graph validation cares.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DeviceProfile {
    /// Shown in error messages: "webgpu defaults", "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub name: String,
    /// The device's limits: attachment bytes per sample, texture sizes, storage binding
    /// sizes and workgroup sizes are checked against them.
    pub limits: Limits,
    /// The device's optional features (device conditions and formats that need a
    /// feature depend on them).
    pub features: Features,
    /// Capabilities of the formats the device reports; formats not listed fall back to
    /// what WebGPU guarantees for `features`.
    pub formats: Vec<(TextureFormat, TextureFormatFeatures)>,
    /// Whether `TextureUsages::TRANSIENT_ATTACHMENT` may be used.
    pub transient_attachments: bool,
    /// The adapter is the CPU (device condition `cpu_device`). Profiles recorded before
    /// this field existed read as a GPU's.
    #[serde(default)]
    pub cpu: bool,
}

impl DeviceProfile {
    /// What every WebGPU device guarantees: default limits, no optional features.
    pub fn webgpu() -> Self {
        Self {
            name: "webgpu defaults".into(),
            limits: Limits::default(),
            features: Features::empty(),
            formats: Vec::new(),
            transient_attachments: true,
            cpu: false,
        }
    }

    /// Whether this device is or has what `condition` stands for.
    pub fn has(&self, condition: DeviceTrait) -> bool {
        match condition {
            DeviceTrait::Features(needs) => self.features.contains(needs),
            DeviceTrait::Cpu => self.cpu,
            DeviceTrait::ColorBytesPerSample(bytes) => {
                self.limits.max_color_attachment_bytes_per_sample >= bytes
            }
        }
    }

    /// `features` with the [device conditions](DEVICE_CONDITIONS) as this device has them:
    /// the caller's own device names are replaced.
    pub fn conditions(&self, features: &condition::Features) -> condition::Features {
        let theirs = features
            .iter()
            .filter(|f| !condition::is_device_condition(f));
        let ours = DEVICE_CONDITIONS
            .iter()
            .filter(|(_, condition)| self.has(*condition))
            .map(|(name, _)| *name);
        theirs.chain(ours).collect()
    }

    /// This profile with what the device conditions `features` names stand for (device
    /// features, or being the CPU): validation compiles a file's branch for such a device
    /// on any profile.
    pub fn granting(&self, features: &condition::Features) -> DeviceProfile {
        let mut profile = self.clone();
        for (name, condition) in DEVICE_CONDITIONS {
            if features.contains(name) {
                match condition {
                    DeviceTrait::Features(needs) => profile.features |= needs,
                    DeviceTrait::Cpu => profile.cpu = true,
                    DeviceTrait::ColorBytesPerSample(bytes) => {
                        let limit = &mut profile.limits.max_color_attachment_bytes_per_sample;
                        *limit = (*limit).max(bytes);
                    }
                }
                profile.name = format!("{} with {name}", profile.name);
            }
        }
        profile
    }

    /// The capabilities of `format` on this device.
    pub fn format(&self, format: TextureFormat) -> TextureFormatFeatures {
        self.formats
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, caps)| *caps)
            .unwrap_or_else(|| format.guaranteed_format_features(self.features))
    }

    /// Sample counts `format` supports as a render target or sampled texture, ascending.
    pub fn sample_counts(&self, format: TextureFormat) -> Vec<u32> {
        [1, 2, 4, 8, 16]
            .into_iter()
            .filter(|&n| self.supports_samples(format, n))
            .collect()
    }

    /// Whether textures of `format` may have `samples` samples (1 always may).
    pub fn supports_samples(&self, format: TextureFormat, samples: u32) -> bool {
        samples == 1 || self.format(format).flags.sample_count_supported(samples)
    }

    /// Whether the device has the features `format` needs and supports it with `samples`.
    pub fn can_make(&self, format: TextureFormat, samples: u32) -> bool {
        self.features.contains(format.required_features()) && self.supports_samples(format, samples)
    }

    /// Whether `format` may be a render attachment.
    pub fn can_render(&self, format: TextureFormat) -> bool {
        self.format(format)
            .allowed_usages
            .contains(TextureUsages::RENDER_ATTACHMENT)
    }

    /// Whether `format` may be bound as a storage texture.
    pub fn can_store(&self, format: TextureFormat) -> bool {
        self.format(format)
            .allowed_usages
            .contains(TextureUsages::STORAGE_BINDING)
    }

    /// Whether a storage binding of `format` may be read, written or both, as declared.
    pub fn storage_access(&self, format: TextureFormat, read: bool, write: bool) -> bool {
        let flag = match (read, write) {
            (true, true) => TextureFormatFeatureFlags::STORAGE_READ_WRITE,
            (true, false) => TextureFormatFeatureFlags::STORAGE_READ_ONLY,
            _ => TextureFormatFeatureFlags::STORAGE_WRITE_ONLY,
        };
        self.format(format).flags.contains(flag)
    }

    /// Whether a multisampled `format` may be resolved in a render pass.
    pub fn can_resolve(&self, format: TextureFormat) -> bool {
        self.format(format)
            .flags
            .contains(TextureFormatFeatureFlags::MULTISAMPLE_RESOLVE)
    }
}

/// The bytes per sample a render pass with color attachments of `formats` (in location
/// order) counts against `max_color_attachment_bytes_per_sample`.
pub fn color_bytes_per_sample(formats: impl IntoIterator<Item = TextureFormat>) -> u32 {
    formats.into_iter().fold(0, |total, format| {
        let (cost, align) = color_target_cost(format);
        total.next_multiple_of(align.max(1)) + cost
    })
}

/// Bytes a color attachment of `format` counts against
/// `max_color_attachment_bytes_per_sample`, per the WebGPU rule: each target starts at a
/// multiple of its component alignment.
pub fn color_target_cost(format: TextureFormat) -> (u32, u32) {
    let bytes = format.target_pixel_byte_cost().unwrap_or(0);
    let align = format.target_component_alignment().unwrap_or(1);
    (bytes, align)
}

#[cfg(test)]
mod tests {
    use super::DeviceProfile;
    use crate::condition::{DeviceTrait, Features};

    /// `color_bytes_64` holds where the device allows 64 bytes per sample of color
    /// targets, and validating its branch on a profile without it raises the limit.
    #[test]
    fn wide_color_targets_are_a_limit_the_profile_has_or_is_granted() {
        let wide = DeviceTrait::ColorBytesPerSample(64);
        let webgpu = DeviceProfile::webgpu();
        assert!(!webgpu.has(wide));
        let granted = webgpu.granting(&Features::from_iter(["color_bytes_64"]));
        assert!(granted.has(wide));
        assert_eq!(granted.limits.max_color_attachment_bytes_per_sample, 64);
        assert_eq!(granted.name, "webgpu defaults with color_bytes_64");
        let mut vulkan = DeviceProfile::webgpu();
        vulkan.limits.max_color_attachment_bytes_per_sample = 128;
        let conditions = vulkan.conditions(&Features::new());
        assert!(conditions.contains("color_bytes_64"));
        let kept = vulkan.granting(&Features::from_iter(["color_bytes_64"]));
        assert_eq!(kept.limits.max_color_attachment_bytes_per_sample, 128);
    }

    /// A profile file saved before `cpu` existed (`rgraph adapters --save-profile`) reads as
    /// a GPU's, and a CPU adapter's keeps the flag through a save and load.
    #[test]
    fn profiles_saved_without_cpu_read_as_a_gpu_s() {
        let mut json = serde_json::to_value(DeviceProfile::webgpu()).unwrap();
        json.as_object_mut().unwrap().remove("cpu");
        let old: DeviceProfile = serde_json::from_value(json).unwrap();
        assert!(!old.cpu);
        let cpu = DeviceProfile {
            cpu: true,
            ..DeviceProfile::webgpu()
        };
        let text = serde_json::to_string(&cpu).unwrap();
        assert!(serde_json::from_str::<DeviceProfile>(&text).unwrap().cpu);
    }
}
