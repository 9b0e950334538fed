//! Opening a headless device: the one place that decides which adapter runs the graph.
//!
//! The default is lavapipe (Mesa's software Vulkan driver) unless `RGRAPH_ADAPTER` says
//! otherwise, so tests and CI produce the same pixels on any machine; a `--adapter` flag,
//! passed to [`AdapterChoice::resolve`], overrides the variable.

use std::fmt;
use std::str::FromStr;
use std::sync::{Arc, Mutex};

use wgpu::{Backends, DeviceType, Features, TextureFormat};

use crate::profile::DeviceProfile;

/// Which adapter to open.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AdapterChoice {
    /// Mesa's software rasterizer (`DeviceType::Cpu`, or a name containing "llvmpipe").
    Lavapipe,
    /// The first adapter that is not a CPU one.
    FirstGpu,
    /// The first adapter whose name contains this text (case-insensitive).
    Named(String),
}

impl AdapterChoice {
    /// The environment variable that picks the adapter when no flag does.
    pub const ENV: &'static str = "RGRAPH_ADAPTER";

    /// `flag` when given and not empty (a CLI `--adapter`), else `RGRAPH_ADAPTER`, else lavapipe.
    pub fn resolve(flag: Option<&str>) -> Self {
        flag.and_then(|text| text.parse().ok())
            .unwrap_or_else(Self::from_env)
    }

    /// `RGRAPH_ADAPTER` when set and not empty, else lavapipe.
    pub fn from_env() -> Self {
        std::env::var(Self::ENV)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(AdapterChoice::Lavapipe)
    }

    /// Whether the adapter described by `info` is the one asked for.
    pub fn matches(&self, info: &wgpu::AdapterInfo) -> bool {
        match self {
            AdapterChoice::Lavapipe => is_lavapipe(info),
            AdapterChoice::FirstGpu => !is_lavapipe(info) && info.device_type != DeviceType::Cpu,
            AdapterChoice::Named(part) => info.name.to_lowercase().contains(&part.to_lowercase()),
        }
    }
}

/// `"lavapipe"` and `"gpu"` (any case) are the keywords; any other text is part of an
/// adapter name. Empty text is no choice at all, so callers fall back to the default.
impl FromStr for AdapterChoice {
    type Err = EmptyChoice;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let text = text.trim();
        match text.to_lowercase().as_str() {
            "" => Err(EmptyChoice),
            "lavapipe" => Ok(AdapterChoice::Lavapipe),
            "gpu" => Ok(AdapterChoice::FirstGpu),
            _ => Ok(AdapterChoice::Named(text.to_string())),
        }
    }
}

/// The adapter choice was empty text.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("empty adapter choice: expected lavapipe, gpu, or part of an adapter's name")]
pub struct EmptyChoice;

impl fmt::Display for AdapterChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AdapterChoice::Lavapipe => f.write_str("lavapipe"),
            AdapterChoice::FirstGpu => f.write_str("gpu"),
            AdapterChoice::Named(name) => write!(f, "\"{name}\""),
        }
    }
}

/// lavapipe reports `DeviceType::Cpu`; the name check also catches builds that do not.
pub fn is_lavapipe(info: &wgpu::AdapterInfo) -> bool {
    info.device_type == DeviceType::Cpu || info.name.to_lowercase().contains("llvmpipe")
}

/// Why no device could be opened.
#[derive(Debug, thiserror::Error)]
pub enum DeviceError {
    /// No Vulkan adapter at all: no driver installed, or the loader found none.
    #[error(
        "no Vulkan adapter found: install the lavapipe driver with \
         `apt-get install mesa-vulkan-drivers`, or pick one with --adapter / RGRAPH_ADAPTER"
    )]
    NoAdapter,

    /// Adapters exist, but none matches the choice.
    #[error(
        "no Vulkan adapter matches {wanted}; available: {}. Pick one with --adapter / \
         RGRAPH_ADAPTER (lavapipe, gpu, or part of an adapter's name){}",
        available.join(", "),
        if *wanted == AdapterChoice::Lavapipe {
            "; lavapipe comes with `apt-get install mesa-vulkan-drivers`"
        } else {
            ""
        }
    )]
    NotFound {
        /// The choice asked for.
        wanted: AdapterChoice,
        /// The adapters found, by name.
        available: Vec<String>,
    },

    /// The adapter refused to open a device with the features and limits asked for.
    #[error("adapter \"{adapter}\" refused to open a device: {source}")]
    RequestDevice {
        /// The adapter's name.
        adapter: String,
        /// wgpu's error.
        source: wgpu::RequestDeviceError,
    },
}

/// Device errors nobody captured in an error scope, kept instead of panicking (wgpu's
/// default handler panics) so that the executor can return them.
#[derive(Clone, Default)]
pub(crate) struct ErrorLog(Arc<Mutex<Vec<String>>>);

impl ErrorLog {
    fn push(&self, message: String) {
        // A poisoned lock only means another thread panicked while pushing: keep logging.
        self.0
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(message);
    }

    pub(crate) fn take(&self) -> Vec<String> {
        std::mem::take(&mut *self.0.lock().unwrap_or_else(|e| e.into_inner()))
    }
}

/// Why a device was lost, as its device-lost callback said.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceLoss {
    /// Destroyed by the application, or lost for a reason the driver does not tell.
    pub reason: wgpu::DeviceLostReason,
    /// The driver's words, often empty.
    pub message: String,
}

impl fmt::Display for DeviceLoss {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.reason {
            wgpu::DeviceLostReason::Destroyed => f.write_str("it was destroyed")?,
            // A driver error, a GPU reset, a shader that ran past the driver's timeout.
            wgpu::DeviceLostReason::Unknown => {
                f.write_str("the driver lost it (a GPU reset, a shader timeout or a driver error)")?
            }
        }
        match self.message.trim() {
            "" => Ok(()),
            message => write!(f, ": {message}"),
        }
    }
}

/// Whether a device was lost, for the [`Executor`](super::Executor)s on it: filled by the
/// device's lost callback. [`Gpu::open`] installs one; an engine that opened its device
/// itself calls [`record`](Self::record) from its own callback and hands a clone to
/// [`Executor::watching`](super::Executor::watching).
#[derive(Clone, Debug, Default)]
pub struct LossWatch(Arc<Mutex<Option<DeviceLoss>>>);

impl LossWatch {
    /// Records that the device was lost; the first loss is kept.
    pub fn record(&self, reason: wgpu::DeviceLostReason, message: String) {
        let mut lost = self.0.lock().unwrap_or_else(|e| e.into_inner());
        lost.get_or_insert(DeviceLoss { reason, message });
    }

    /// The loss, once the device is lost.
    pub fn lost(&self) -> Option<DeviceLoss> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
}

/// An open device and what it was opened from.
///
/// The `Gpu` owns nothing the graph allocates: an [`Executor`](super::Executor) created
/// from it keeps its own clones of the device and queue.
pub struct Gpu {
    /// The wgpu instance the adapter came from (Vulkan backend).
    pub instance: wgpu::Instance,
    /// The adapter chosen.
    pub adapter: wgpu::Adapter,
    /// The device: clone it to keep it, as the executor does.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, backend and driver.
    pub info: wgpu::AdapterInfo,
    pub(crate) errors: ErrorLog,
    /// Filled when the device is lost.
    pub loss: LossWatch,
}

impl Gpu {
    /// Optional features requested whenever the adapter has them: GPU timestamps
    /// everywhere, `Depth32FloatStencil8`, the adapter's real format capabilities
    /// (MSAA and resolve for formats WebGPU does not guarantee), and what the
    /// [device conditions](crate::DEVICE_CONDITIONS) test (64-bit atomics).
    pub const DEFAULT_FEATURES: Features = Features::TIMESTAMP_QUERY
        .union(Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
        .union(Features::TIMESTAMP_QUERY_INSIDE_PASSES)
        .union(Features::DEPTH32FLOAT_STENCIL8)
        .union(Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
        .union(Features::SHADER_INT64)
        .union(Features::SHADER_INT64_ATOMIC_MIN_MAX);

    /// Opens the chosen adapter with [`Self::DEFAULT_FEATURES`] (those it has) and all its
    /// limits. Blocks until the device exists.
    pub fn open(choice: &AdapterChoice) -> Result<Gpu, DeviceError> {
        Self::open_with(choice, Self::DEFAULT_FEATURES)
    }

    /// Opens the chosen adapter requesting `wanted & adapter.features()`.
    ///
    /// The device gets `adapter.limits()`, not the WebGPU defaults: a G-buffer needs more
    /// than the default 32 color bytes per sample. The Vulkan loader's environment
    /// (`VK_DRIVER_FILES`, `XDG_RUNTIME_DIR`) is the application's to set, before any
    /// thread starts: the library only reads it.
    pub fn open_with(choice: &AdapterChoice, wanted: Features) -> Result<Gpu, DeviceError> {
        let instance = new_instance();
        let adapters = pollster::block_on(instance.enumerate_adapters(Backends::VULKAN));
        if adapters.is_empty() {
            return Err(DeviceError::NoAdapter);
        }
        let Some(adapter) = adapters
            .iter()
            .find(|a| choice.matches(&a.get_info()))
            .cloned()
        else {
            return Err(DeviceError::NotFound {
                wanted: choice.clone(),
                available: adapters.iter().map(|a| describe(&a.get_info())).collect(),
            });
        };
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rgraph"),
            required_features: wanted & adapter.features(),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|source| DeviceError::RequestDevice {
            adapter: describe(&info),
            source,
        })?;
        let errors = ErrorLog::default();
        let log = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e| log.push(e.to_string())));
        let loss = LossWatch::default();
        let watch = loss.clone();
        device.set_device_lost_callback(move |reason, message| watch.record(reason, message));
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            info,
            errors,
            loss,
        })
    }

    /// What this device can do, for compiling graphs that must run on it: the device's
    /// own limits and features (not the adapter's), and the adapter's format
    /// capabilities only when `TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES` is enabled.
    pub fn profile(&self) -> DeviceProfile {
        let features = self.device.features();
        let formats = if features.contains(Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES) {
            format_features(&self.adapter)
        } else {
            Vec::new()
        };
        DeviceProfile {
            name: describe(&self.info),
            limits: self.device.limits(),
            features,
            formats,
            transient_attachments: true,
            cpu: self.info.device_type == DeviceType::Cpu,
        }
    }

    /// Device errors reported outside any error scope since the last call (the executor
    /// drains these after each frame too).
    pub fn take_errors(&self) -> Vec<String> {
        self.errors.take()
    }
}

impl DeviceProfile {
    /// Everything the adapter can do with every optional feature enabled: its limits,
    /// features and the capabilities of every uncompressed format.
    pub fn from_adapter(adapter: &wgpu::Adapter) -> Self {
        DeviceProfile {
            name: describe(&adapter.get_info()),
            limits: adapter.limits(),
            features: adapter.features(),
            formats: format_features(adapter),
            transient_attachments: true,
            cpu: adapter.get_info().device_type == DeviceType::Cpu,
        }
    }
}

/// One adapter as `rgraph adapters` shows it.
#[derive(Clone, Debug)]
pub struct AdapterSummary {
    /// The adapter's name, backend and driver.
    pub info: wgpu::AdapterInfo,
    /// Whether it is Mesa's lavapipe, the CPU rasteriser the tests run on.
    pub lavapipe: bool,
    /// Its limits, features and format capabilities (see [`DeviceProfile::from_adapter`]).
    pub profile: DeviceProfile,
    /// Supported sample counts of [`COMMON_FORMATS`], in that order.
    pub sample_counts: Vec<(TextureFormat, Vec<u32>)>,
}

/// The formats render graphs use most, for a short capability table.
pub const COMMON_FORMATS: &[TextureFormat] = &[
    TextureFormat::Rgba8Unorm,
    TextureFormat::Rgba8UnormSrgb,
    TextureFormat::Bgra8Unorm,
    TextureFormat::Rgb10a2Unorm,
    TextureFormat::Rg16Float,
    TextureFormat::Rgba16Float,
    TextureFormat::R32Float,
    TextureFormat::Rgba32Float,
    TextureFormat::Rgba8Uint,
    TextureFormat::Depth24PlusStencil8,
    TextureFormat::Depth32Float,
    TextureFormat::Depth32FloatStencil8,
];

/// Every Vulkan adapter the loader finds, in the loader's order.
pub fn list_adapters() -> Vec<AdapterSummary> {
    let instance = new_instance();
    pollster::block_on(instance.enumerate_adapters(Backends::VULKAN))
        .iter()
        .map(|adapter| {
            let info = adapter.get_info();
            let profile = DeviceProfile::from_adapter(adapter);
            let sample_counts = COMMON_FORMATS
                .iter()
                .map(|&f| (f, profile.sample_counts(f)))
                .collect();
            AdapterSummary {
                lavapipe: is_lavapipe(&info),
                info,
                profile,
                sample_counts,
            }
        })
        .collect()
}

/// "name [driver driver_info]", e.g.
/// "llvmpipe (LLVM 15.0.6, 256 bits) [llvmpipe Mesa 22.3.6 (LLVM 15.0.6)]".
fn describe(info: &wgpu::AdapterInfo) -> String {
    let driver = format!("{} {}", info.driver, info.driver_info);
    match driver.trim() {
        "" => info.name.clone(),
        driver => format!("{} [{driver}]", info.name),
    }
}

/// The process's one instance, made on first use: every device [`Gpu::open`] opens comes
/// from it. wgpu numbers devices (and every object) per instance and compares them by
/// that number alone, so two devices of two instances can compare equal; from one
/// instance, a device opened after another was lost is another device to the plugins'
/// per-device caches, which then build their objects again on it.
fn new_instance() -> wgpu::Instance {
    static INSTANCE: std::sync::OnceLock<wgpu::Instance> = std::sync::OnceLock::new();
    INSTANCE
        .get_or_init(|| {
            wgpu::Instance::new(wgpu::InstanceDescriptor {
                backends: Backends::VULKAN,
                // WGPU_VALIDATION=1 and friends still work.
                flags: wgpu::InstanceFlags::default().with_env(),
                ..wgpu::InstanceDescriptor::new_without_display_handle()
            })
        })
        .clone()
}

/// Capabilities of every uncompressed format the adapter knows.
fn format_features(adapter: &wgpu::Adapter) -> Vec<(TextureFormat, wgpu::TextureFormatFeatures)> {
    UNCOMPRESSED_FORMATS
        .iter()
        .map(|&f| (f, adapter.get_texture_format_features(f)))
        .collect()
}

/// Every uncompressed, single-plane format of wgpu 30: what a graph can render to,
/// sample, store or copy.
const UNCOMPRESSED_FORMATS: &[TextureFormat] = &[
    TextureFormat::R8Unorm,
    TextureFormat::R8Snorm,
    TextureFormat::R8Uint,
    TextureFormat::R8Sint,
    TextureFormat::R16Uint,
    TextureFormat::R16Sint,
    TextureFormat::R16Unorm,
    TextureFormat::R16Snorm,
    TextureFormat::R16Float,
    TextureFormat::Rg8Unorm,
    TextureFormat::Rg8Snorm,
    TextureFormat::Rg8Uint,
    TextureFormat::Rg8Sint,
    TextureFormat::R32Uint,
    TextureFormat::R32Sint,
    TextureFormat::R32Float,
    TextureFormat::Rg16Uint,
    TextureFormat::Rg16Sint,
    TextureFormat::Rg16Unorm,
    TextureFormat::Rg16Snorm,
    TextureFormat::Rg16Float,
    TextureFormat::Rgba8Unorm,
    TextureFormat::Rgba8UnormSrgb,
    TextureFormat::Rgba8Snorm,
    TextureFormat::Rgba8Uint,
    TextureFormat::Rgba8Sint,
    TextureFormat::Bgra8Unorm,
    TextureFormat::Bgra8UnormSrgb,
    TextureFormat::Rgb9e5Ufloat,
    TextureFormat::Rgb10a2Uint,
    TextureFormat::Rgb10a2Unorm,
    TextureFormat::Rg11b10Ufloat,
    TextureFormat::R64Uint,
    TextureFormat::Rg32Uint,
    TextureFormat::Rg32Sint,
    TextureFormat::Rg32Float,
    TextureFormat::Rgba16Uint,
    TextureFormat::Rgba16Sint,
    TextureFormat::Rgba16Unorm,
    TextureFormat::Rgba16Snorm,
    TextureFormat::Rgba16Float,
    TextureFormat::Rgba32Uint,
    TextureFormat::Rgba32Sint,
    TextureFormat::Rgba32Float,
    TextureFormat::Stencil8,
    TextureFormat::Depth16Unorm,
    TextureFormat::Depth24Plus,
    TextureFormat::Depth24PlusStencil8,
    TextureFormat::Depth32Float,
    TextureFormat::Depth32FloatStencil8,
];

#[cfg(test)]
mod tests {
    use super::AdapterChoice;

    #[test]
    fn choices_parse_keywords_and_name_parts() {
        let parse = |s: &str| s.parse::<AdapterChoice>().ok();
        assert_eq!(parse("lavapipe"), Some(AdapterChoice::Lavapipe));
        assert_eq!(parse(" GPU "), Some(AdapterChoice::FirstGpu));
        assert_eq!(
            parse("RTX 4090"),
            Some(AdapterChoice::Named("RTX 4090".into()))
        );
        assert_eq!(parse("  "), None);
    }

    #[test]
    fn a_flag_overrides_the_environment() {
        assert_eq!(AdapterChoice::resolve(Some("gpu")), AdapterChoice::FirstGpu);
        assert_eq!(
            AdapterChoice::resolve(Some("H100")),
            AdapterChoice::Named("H100".into())
        );
    }

    #[test]
    fn names_match_case_insensitively() {
        let info = wgpu::AdapterInfo {
            name: "NVIDIA H100 80GB HBM3".into(),
            device_type: wgpu::DeviceType::DiscreteGpu,
            ..lavapipe()
        };
        assert!(AdapterChoice::Named("h100".into()).matches(&info));
        assert!(AdapterChoice::FirstGpu.matches(&info));
        assert!(!AdapterChoice::Lavapipe.matches(&info));
        assert!(AdapterChoice::Lavapipe.matches(&lavapipe()));
        assert!(!AdapterChoice::FirstGpu.matches(&lavapipe()));
    }

    fn lavapipe() -> wgpu::AdapterInfo {
        wgpu::AdapterInfo {
            name: "llvmpipe (LLVM 15.0.6, 256 bits)".into(),
            vendor: 0x10005,
            device: 0,
            device_type: wgpu::DeviceType::Cpu,
            device_pci_bus_id: String::new(),
            driver: "llvmpipe".into(),
            driver_info: "Mesa 22.3.6 (LLVM 15.0.6)".into(),
            backend: wgpu::Backend::Vulkan,
            subgroup_min_size: 8,
            subgroup_max_size: 8,
            transient_saves_memory: None,
            limit_bucket: None,
        }
    }
}
