//! The table printed after a frame: each executed pass with its GPU and CPU time, the
//! totals, the textures and memory the plan asked for, and what was culled.

use rgraph_core::explain::bytes;
use rgraph_core::gpu::{DeviceObjects, FrameReport};
use rgraph_core::Plan;

/// The summary, one line each, for stderr. `specialised`: the plan was compiled for the
/// scene's features (without `--no-specialise`). The plan's features alone do not tell:
/// compiled for every feature, a plan holds the presences its file declares (`blend`).
pub fn text(plan: &Plan, report: &FrameReport, specialised: bool) -> String {
    let ms = |ns: Option<u64>| ns.map_or("-".to_string(), |ns| format!("{:.3}", ns as f64 / 1e6));
    let width = report
        .passes
        .iter()
        .map(|p| p.name.len())
        .chain(["pass".len(), "total".len()])
        .max()
        .unwrap_or(0);
    let mut lines = vec![format!(
        "{:<width$}  {:<8}  {:>9}  {:>9}",
        "pass", "kind", "GPU ms", "CPU ms"
    )];
    for pass in &report.passes {
        lines.push(format!(
            "{:<width$}  {:<8}  {:>9}  {:>9}",
            pass.name,
            pass.kind.to_string(),
            ms(pass.gpu_ns),
            ms(Some(pass.cpu_ns))
        ));
    }
    let cpu_total = report.passes.iter().map(|p| p.cpu_ns).sum();
    lines.push(format!(
        "{:<width$}  {:<8}  {:>9}  {:>9}",
        "total",
        "",
        ms(report.gpu_total_ns),
        ms(Some(cpu_total))
    ));
    // One frame is all render draws, so its callbacks also create their pipelines.
    lines.push(
        "(a cold frame: CPU times include creating pipelines and uploading the scene)".into(),
    );
    if report.gpu_total_ns.is_none() {
        lines.push("(no GPU times: the device has no timestamp queries)".into());
    }
    let resources = plan
        .resources
        .iter()
        .filter(|r| r.physical.is_some() && r.texture.is_some())
        .count();
    let held = match report.held_bytes() {
        0 => String::new(),
        held => format!(", and {} the passes keep for themselves", bytes(held)),
    };
    lines.push(format!(
        "textures: {} physical for {resources} resource(s), {} allocated this frame; \
         memory: {} logical, {} physical{held}",
        plan.textures.len(),
        report.textures_allocated,
        bytes(plan.memory.logical_bytes),
        bytes(plan.memory.physical_bytes),
    ));
    // The device conditions are the device's, whatever --no-specialise says.
    let (device, scene): (Vec<&str>, Vec<&str>) = plan
        .features
        .iter()
        .map(String::as_str)
        .partition(|f| rgraph_core::is_device_condition(f));
    if specialised && !scene.is_empty() {
        lines.push(format!(
            "specialised to the scene's features: {} (--no-specialise compiles for every \
             feature)",
            scene.join(", ")
        ));
    }
    if !device.is_empty() {
        lines.push(format!("device conditions: {}", device.join(", ")));
    }
    // Passes a false condition dropped are the file's other variants, not waste.
    for (dropped, label) in [(false, "culled"), (true, "dropped by conditions")] {
        let names: Vec<&str> = plan
            .culled
            .iter()
            .filter(|c| c.dropped == dropped)
            .map(|c| c.name.as_str())
            .collect();
        if !names.is_empty() {
            lines.push(format!("{label}: {}", names.join(", ")));
        }
    }
    lines.join("\n")
}

/// One frame of a sequence on one line: its index, the CPU time to record and submit it,
/// its GPU time when the device has timestamps, then what the process holds after it:
/// its resident memory where the platform tells, and the device objects alive with their
/// memory. Both stay flat after the first frame; a soak run watches them.
pub fn frame_line(
    index: u32,
    report: &FrameReport,
    resident: Option<u64>,
    device: &DeviceObjects,
) -> String {
    let mib = |bytes: f64| bytes / f64::from(1u32 << 20);
    let gpu = match report.gpu_total_ns {
        Some(ns) => format!("GPU {:.3} ms", ns as f64 / 1e6),
        None => "GPU - (no timestamp queries)".to_string(),
    };
    let resident = match resident {
        Some(bytes) => format!("resident {:.1} MiB, ", mib(bytes as f64)),
        None => String::new(),
    };
    format!(
        "frame {index:04}: record+submit {:.3} ms, {gpu}; {resident}device {} objects, \
         {:.1} MiB",
        report.record_submit_ns as f64 / 1e6,
        device.objects(),
        mib(device.bytes() as f64)
    )
}
