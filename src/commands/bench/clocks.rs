//! The GPU's clocks, throttle reasons and temperature, where the platform reports them:
//! on an NVIDIA adapter through `nvidia-smi`, sampled once per round while the round's
//! frames run (the query is started with the round and read when it ends, so it adds no
//! idle time between frames). Elsewhere (lavapipe, other vendors, no `nvidia-smi`) they
//! are "not reported", with the reason.

use std::process::{Child, Command, Stdio};

use graph_core::gpu::Gpu;
use serde::Serialize;

/// PCI vendor ID of NVIDIA.
const NVIDIA: u32 = 0x10de;
const TOOL: &str = "nvidia-smi";
/// The field of the active throttle reasons; newer drivers name it "event reasons" and
/// may drop the old name, which is tried first.
const THROTTLE_FIELDS: [&str; 2] = [
    "clocks_throttle_reasons.active",
    "clocks_event_reasons.active",
];

/// Whether and how clocks are sampled in this run (results.json's `gpu_clocks`).
#[derive(Clone, Debug, Serialize)]
pub struct ClockSource {
    /// "nvidia-smi", or `null` when not reported.
    pub reported_by: Option<String>,
    /// The query, or why the clocks are not reported.
    pub detail: String,
    /// The GPU's memory as `nvidia-smi` reports it, in bytes.
    pub memory_total_bytes: Option<u64>,
    /// The GPU queried (`nvidia-smi -i`): the adapter's PCI bus ID where wgpu gives one.
    #[serde(skip)]
    gpu: Option<String>,
    #[serde(skip)]
    query: String,
}

/// One sample taken while a round ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClockSample {
    pub sm_mhz: Option<u32>,
    pub mem_mhz: Option<u32>,
    /// The active throttle reasons as `nvidia-smi` prints them ("0x0000000000000004").
    pub throttle_reasons: String,
    /// Their names (NVML's `nvmlClocksEventReason*` bits); "gpu_idle" is usual between
    /// frames.
    pub throttle: Vec<&'static str>,
    pub temperature_c: Option<u32>,
}

/// NVML's clock event (throttle) reason bits, by name.
const REASONS: [(u64, &str); 9] = [
    (0x1, "gpu_idle"),
    (0x2, "applications_clocks_setting"),
    (0x4, "sw_power_cap"),
    (0x8, "hw_slowdown"),
    (0x10, "sync_boost"),
    (0x20, "sw_thermal_slowdown"),
    (0x40, "hw_thermal_slowdown"),
    (0x80, "hw_power_brake_slowdown"),
    (0x100, "display_clock_setting"),
];

/// A query started with a round; [`Pending::finish`] reads it.
pub struct Pending(Child);

impl ClockSource {
    /// Clocks for `gpu`'s adapter: `nvidia-smi` for an NVIDIA adapter where it answers a
    /// first query, else not reported, saying why.
    pub fn for_gpu(gpu: &Gpu) -> ClockSource {
        let info = &gpu.info;
        if info.vendor != NVIDIA {
            return ClockSource::not_reported(format!(
                "not reported: {} is not an NVIDIA adapter (only nvidia-smi is read)",
                info.name
            ));
        }
        let bus = Some(info.device_pci_bus_id.clone()).filter(|b| !b.is_empty());
        let mut why = String::new();
        for field in THROTTLE_FIELDS {
            let mut source = ClockSource {
                reported_by: Some(TOOL.into()),
                detail: String::new(),
                memory_total_bytes: None,
                gpu: bus.clone(),
                query: format!("clocks.sm,clocks.mem,{field},temperature.gpu"),
            };
            let probe = source
                .start()
                .map_err(|e| e.to_string())
                .and_then(|p| p.read());
            match probe.and_then(|line| parse(&line)) {
                Ok(_) => {
                    source.memory_total_bytes = source.memory_total();
                    source.detail = format!(
                        "{TOOL} --query-gpu={} {}, once per round while its frames run",
                        source.query,
                        source
                            .gpu
                            .as_ref()
                            .map_or("(the first GPU)".into(), |b| format!("-i {b}")),
                    );
                    return source;
                }
                Err(e) => why = e,
            }
        }
        ClockSource::not_reported(format!("not reported: {TOOL} failed: {why}"))
    }

    fn not_reported(detail: String) -> ClockSource {
        ClockSource {
            reported_by: None,
            detail,
            memory_total_bytes: None,
            gpu: None,
            query: String::new(),
        }
    }

    /// Starts a sample, when clocks are reported and the query starts.
    pub fn sample(&self) -> Option<Pending> {
        self.reported_by.as_ref()?;
        self.start().ok()
    }

    fn start(&self) -> std::io::Result<Pending> {
        self.command(&self.query).spawn().map(Pending)
    }

    fn command(&self, query: &str) -> Command {
        let mut command = Command::new(TOOL);
        command.arg(format!("--query-gpu={query}"));
        command.arg("--format=csv,noheader,nounits");
        if let Some(gpu) = &self.gpu {
            command.args(["-i", gpu]);
        }
        command.stdout(Stdio::piped()).stderr(Stdio::piped());
        command
    }

    /// The GPU's memory in bytes (`memory.total`, reported in MiB).
    fn memory_total(&self) -> Option<u64> {
        let out = self.command("memory.total").output().ok()?;
        let text = String::from_utf8_lossy(&out.stdout);
        let mib: u64 = text.lines().next()?.trim().parse().ok()?;
        Some(mib << 20)
    }
}

impl Pending {
    /// The sample, `None` when the query failed or printed something else.
    pub fn finish(self) -> Option<ClockSample> {
        parse(&self.read().ok()?).ok()
    }

    /// The query's first line of output, or its error.
    fn read(self) -> Result<String, String> {
        let out = self.0.wait_with_output().map_err(|e| e.to_string())?;
        let stdout = String::from_utf8_lossy(&out.stdout);
        match out.status.success() {
            true => Ok(stdout.lines().next().unwrap_or("").to_string()),
            false => {
                let stderr = String::from_utf8_lossy(&out.stderr);
                let said = stderr.lines().chain(stdout.lines()).next().unwrap_or("");
                Err(format!("{} ({said})", out.status))
            }
        }
    }
}

/// One line of `clocks.sm, clocks.mem, throttle reasons, temperature.gpu` without units;
/// a field the GPU does not report ("[N/A]") is `None`.
fn parse(line: &str) -> Result<ClockSample, String> {
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    let [sm, mem, throttle, temperature] = fields[..] else {
        return Err(format!("unexpected output \"{line}\""));
    };
    let mask = u64::from_str_radix(throttle.trim_start_matches("0x"), 16).ok();
    Ok(ClockSample {
        sm_mhz: sm.parse().ok(),
        mem_mhz: mem.parse().ok(),
        throttle_reasons: throttle.to_string(),
        throttle: mask.map_or(Vec::new(), |mask| {
            REASONS
                .iter()
                .filter(|(bit, _)| mask & bit != 0)
                .map(|(_, name)| *name)
                .collect()
        }),
        temperature_c: temperature.parse().ok(),
    })
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn a_sample_line_is_read_with_its_throttle_reasons() {
        let sample = parse("1980, 2619, 0x0000000000000044, 47").unwrap();
        assert_eq!(
            (sample.sm_mhz, sample.mem_mhz, sample.temperature_c),
            (Some(1980), Some(2619), Some(47))
        );
        assert_eq!(sample.throttle, ["sw_power_cap", "hw_thermal_slowdown"]);
        let missing = parse("[N/A], 2619, [N/A], 40").unwrap();
        assert_eq!((missing.sm_mhz, missing.throttle.len()), (None, 0));
        assert!(parse("No devices were found").is_err());
    }
}
