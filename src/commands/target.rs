//! Turning `--profile` and `--size` into compile options.

use std::path::Path;

use rgraph_core::bounded_read;
use rgraph_core::gpu::{AdapterChoice, Gpu};
use rgraph_core::{CompileOptions, DeviceProfile};

use super::CommandError;
use crate::cli::Target;

/// `webgpu`, `adapter` (opens the chosen adapter) or a profile file written by
/// `rgraph adapters --save-profile`.
pub fn compile_options(target: &Target) -> Result<CompileOptions, CommandError> {
    let profile = match target.profile.as_str() {
        "webgpu" => DeviceProfile::webgpu(),
        "adapter" => {
            let choice = AdapterChoice::resolve(target.adapter.as_deref());
            Gpu::open(&choice)
                .map_err(|e| CommandError::Usage(e.to_string()))?
                .profile()
        }
        path => read_profile(Path::new(path))?,
    };
    Ok(CompileOptions {
        output_size: target.size,
        profile,
    })
}

/// The largest profile file read: 1 MiB, a hundred times a saved profile.
const MAX_PROFILE_BYTES: u64 = 1 << 20;

fn read_profile(path: &Path) -> Result<DeviceProfile, CommandError> {
    let text = bounded_read::read_text(path, MAX_PROFILE_BYTES).map_err(|e| {
        CommandError::Usage(format!(
            "--profile: \"{}\" is not webgpu, adapter or a readable profile file: {e}",
            path.display()
        ))
    })?;
    serde_json::from_str(&text).map_err(|e| {
        CommandError::Usage(format!(
            "{}:{}:{}: error: not a device profile: {e}",
            path.display(),
            e.line(),
            e.column()
        ))
    })
}
