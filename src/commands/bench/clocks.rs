//! The GPU's clocks, throttle reasons and temperature, where the platform reports them:
//! on an NVIDIA adapter through `nvidia-smi`, sampled once per round while the round's
//! frames run (the query is started with the round and read when it ends, so it adds no
//! idle time between frames). Elsewhere (lavapipe, other vendors, no `nvidia-smi`) they
//! are "not reported", with the reason.

use std::process::{Child, Command, Stdio};

use rgraph_core::gpu::Gpu;
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
    /// The adapter's PCI address where wgpu gives one: the line of `nvidia-smi`'s output
    /// to read on a machine with several GPUs (else the first).
    #[serde(skip)]
    bus: Option<PciAddress>,
    #[serde(skip)]
    query: String,
}

/// Domain, bus, device and function: "0000:18:00.0" as wgpu writes it, "00000000:18:00.0"
/// as `nvidia-smi` does.
type PciAddress = [u32; 4];

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

/// A query started with a round; [`ClockSource::finish`] reads it.
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
        let gpu_at = match info.device_pci_bus_id.as_str() {
            "" => "the first GPU".to_string(),
            bus => format!("the GPU at {bus}"),
        };
        let mut why = String::new();
        for field in THROTTLE_FIELDS {
            let mut source = ClockSource {
                reported_by: Some(TOOL.into()),
                detail: String::new(),
                memory_total_bytes: None,
                bus: pci_address(&info.device_pci_bus_id),
                query: format!("pci.bus_id,clocks.sm,clocks.mem,{field},temperature.gpu"),
            };
            let probe = source.start().map_err(|e| e.to_string());
            match probe.and_then(|p| source.read(p)) {
                Ok(_) => {
                    source.memory_total_bytes = source.memory_total();
                    source.detail = format!(
                        "{TOOL} --query-gpu={}, {gpu_at}, once per round while its frames run",
                        source.query
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
            bus: None,
            query: String::new(),
        }
    }

    /// Starts a sample, when clocks are reported and the query starts.
    pub fn sample(&self) -> Option<Pending> {
        self.reported_by.as_ref()?;
        self.start().ok()
    }

    /// The sample `pending` took; `None` when the query failed or printed something else.
    pub fn finish(&self, pending: Pending) -> Option<ClockSample> {
        self.read(pending).ok()
    }

    fn start(&self) -> std::io::Result<Pending> {
        self.command(&self.query).spawn().map(Pending)
    }

    fn read(&self, pending: Pending) -> Result<ClockSample, String> {
        parse(&output(pending.0)?, self.bus)
    }

    fn command(&self, query: &str) -> Command {
        let mut command = Command::new(TOOL);
        command.arg(format!("--query-gpu={query}"));
        command.arg("--format=csv,noheader,nounits");
        command.stdout(Stdio::piped()).stderr(Stdio::piped());
        command
    }

    /// The GPU's memory in bytes (`memory.total`, reported in MiB).
    fn memory_total(&self) -> Option<u64> {
        let child = self.command("pci.bus_id,memory.total").spawn().ok()?;
        let out = output(child).ok()?;
        let [mib] = gpu_line(&out, self.bus)?[..] else {
            return None;
        };
        Some(mib.parse::<u64>().ok()? << 20)
    }
}

/// What `child` printed, or why it failed.
fn output(child: Child) -> Result<String, String> {
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    match out.status.success() {
        true => Ok(stdout.into_owned()),
        false => {
            let stderr = String::from_utf8_lossy(&out.stderr);
            let said = stderr.lines().chain(stdout.lines()).next().unwrap_or("");
            Err(format!("{} ({said})", out.status))
        }
    }
}

/// The fields after the bus ID on the line of the GPU at `bus` in `nvidia-smi`'s CSV
/// output (one line per GPU, each starting with its bus ID); the first line where `bus`
/// is unknown or no line has it.
fn gpu_line(out: &str, bus: Option<PciAddress>) -> Option<Vec<&str>> {
    let lines: Vec<Vec<&str>> = out
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(str::trim).collect())
        .collect();
    let at_bus = |line: &&Vec<&str>| bus.is_some() && pci_address(line[0]) == bus;
    let line = lines.iter().find(at_bus).or(lines.first())?;
    Some(line[1..].to_vec())
}

/// A PCI address "DOMAIN:BUS:DEVICE.FUNCTION" in hexadecimal, whatever its digits.
fn pci_address(text: &str) -> Option<PciAddress> {
    let (rest, function) = text.trim().rsplit_once('.')?;
    let mut parts = rest.split(':');
    let mut next = || u32::from_str_radix(parts.next()?, 16).ok();
    let address = [
        next()?,
        next()?,
        next()?,
        u32::from_str_radix(function, 16).ok()?,
    ];
    parts.next().is_none().then_some(address)
}

/// The line of the GPU at `bus` of `pci.bus_id, clocks.sm, clocks.mem, throttle reasons,
/// temperature.gpu` without units; a field the GPU does not report ("[N/A]") is `None`.
fn parse(out: &str, bus: Option<PciAddress>) -> Result<ClockSample, String> {
    let unexpected = || format!("unexpected output \"{}\"", out.trim());
    let fields = gpu_line(out, bus).ok_or_else(unexpected)?;
    let [sm, mem, throttle, temperature] = fields[..] else {
        return Err(unexpected());
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
    use super::{parse, pci_address};

    #[test]
    fn a_sample_line_is_read_with_its_throttle_reasons() {
        let out = "00000000:18:00.0, 1980, 2619, 0x0000000000000044, 47\n";
        let sample = parse(out, None).unwrap();
        assert_eq!(
            (sample.sm_mhz, sample.mem_mhz, sample.temperature_c),
            (Some(1980), Some(2619), Some(47))
        );
        assert_eq!(sample.throttle, ["sw_power_cap", "hw_thermal_slowdown"]);
        let missing = parse("00000000:18:00.0, [N/A], 2619, [N/A], 40", None).unwrap();
        assert_eq!((missing.sm_mhz, missing.throttle.len()), (None, 0));
        assert!(parse("No devices were found", None).is_err());
        assert!(parse("", None).is_err());
    }

    #[test]
    fn the_adapters_gpu_is_found_by_its_bus_among_several() {
        let out = "00000000:18:00.0, 1980, 2619, 0x0, 40\n\
                   00000000:2A:00.0, 1410, 2619, 0x20, 85\n";
        // wgpu writes a four-digit domain and lower-case hexadecimal.
        let bus = pci_address("0000:2a:00.0");
        assert_eq!(bus, Some([0, 0x2a, 0, 0]));
        assert_eq!(parse(out, bus).unwrap().sm_mhz, Some(1410));
        // An address no line has, or none, reads the first GPU.
        let elsewhere = pci_address("0000:99:00.0");
        assert_eq!(parse(out, elsewhere).unwrap().sm_mhz, Some(1980));
        assert_eq!(parse(out, None).unwrap().sm_mhz, Some(1980));
        assert_eq!(pci_address(""), None);
        assert_eq!(pci_address("0:1:2:3.0"), None);
    }
}
