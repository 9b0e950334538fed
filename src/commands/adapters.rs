//! `rgraph adapters`: what this machine's Vulkan adapters can do.

use std::path::Path;

use rgraph_core::gpu::{list_adapters, AdapterChoice};

use super::{write_atomically, CommandError};

pub fn run(save_profile: Option<&Path>, adapter: Option<&str>) -> Result<(), CommandError> {
    let adapters = list_adapters();
    if adapters.is_empty() {
        return Err(CommandError::Usage(
            "no Vulkan adapter found: install the lavapipe driver with `apt-get install \
             mesa-vulkan-drivers`, or a GPU driver"
                .into(),
        ));
    }
    for (i, a) in adapters.iter().enumerate() {
        let kind = if a.lavapipe { " (lavapipe)" } else { "" };
        println!(
            "{i}: {}{kind}\n   type {:?}, driver {} {}",
            a.info.name, a.info.device_type, a.info.driver, a.info.driver_info
        );
        let limits = &a.profile.limits;
        println!(
            "   limits: 2D textures up to {}, {} color attachments, {} color bytes per sample",
            limits.max_texture_dimension_2d,
            limits.max_color_attachments,
            limits.max_color_attachment_bytes_per_sample
        );
        let features: Vec<&str> = a.profile.features.iter_names().map(|(n, _)| n).collect();
        println!("   features: {}", features.join(", "));
        println!("   sample counts:");
        for (format, counts) in &a.sample_counts {
            let counts: Vec<String> = counts.iter().map(|n| format!("{n}x")).collect();
            println!("     {format:?}: {}", counts.join(" "));
        }
    }
    if let Some(path) = save_profile {
        let choice = AdapterChoice::resolve(adapter);
        let chosen = adapters
            .iter()
            .find(|a| choice.matches(&a.info))
            .ok_or_else(|| {
                let names: Vec<&str> = adapters.iter().map(|a| a.info.name.as_str()).collect();
                CommandError::Usage(format!(
                    "no adapter matches {choice} (adapters: {})",
                    names.join(", ")
                ))
            })?;
        let json = serde_json::to_string_pretty(&chosen.profile)
            .map_err(|e| CommandError::Usage(format!("cannot encode the profile: {e}")))?;
        write_atomically(path, json.as_bytes())?;
        eprintln!(
            "wrote the profile of {} to {}",
            chosen.info.name,
            path.display()
        );
    }
    Ok(())
}
