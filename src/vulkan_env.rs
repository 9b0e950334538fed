//! The Vulkan loader's environment: the command line's decision, not the library's, made
//! once at start-up, before any thread or Vulkan instance exists (changing the
//! environment while another thread reads it is undefined, and the loader reads it only
//! when an instance is created).

use std::path::Path;

use rgraph_core::gpu::AdapterChoice;

use crate::cli::{Cli, Command, RenderArgs, ViewArgs};

/// Where Mesa installs lavapipe's driver manifest on x86-64 Linux.
const LAVAPIPE_ICD: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// Sets `XDG_RUNTIME_DIR` when unset (without it the loader warns on every instance in
/// containers and CI) and, when the command runs on lavapipe and no driver list is set,
/// narrows the loader to lavapipe's driver, which skips probing (and sometimes crashing
/// in) other drivers. `rgraph adapters` lists every driver, so it narrows nothing.
pub fn prepare(cli: &Cli) {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        std::env::set_var("XDG_RUNTIME_DIR", "/tmp");
    }
    let adapter = match &cli.command {
        Command::Validate { target, .. } | Command::Explain { target, .. } => &target.adapter,
        Command::Render(RenderArgs { frame, .. }) | Command::View(ViewArgs { frame, .. }) => {
            &frame.adapter
        }
        Command::Bench(args) => &args.adapter,
        Command::Adapters { .. } | Command::Compare { .. } => return,
    };
    let driver_list_set = std::env::var_os("VK_DRIVER_FILES").is_some()
        || std::env::var_os("VK_ICD_FILENAMES").is_some();
    if AdapterChoice::resolve(adapter.as_deref()) == AdapterChoice::Lavapipe
        && !driver_list_set
        && Path::new(LAVAPIPE_ICD).exists()
    {
        std::env::set_var("VK_DRIVER_FILES", LAVAPIPE_ICD);
    }
}
