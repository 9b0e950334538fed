//! Where and when a bench ran: the machine, the adapter, the commit, the time.

use std::time::{SystemTime, UNIX_EPOCH};

use rgraph_core::gpu::Gpu;
use serde::Serialize;

/// Overrides `git rev-parse HEAD`, for machines that run a binary without its repository.
pub const COMMIT_ENV: &str = "RGRAPH_GIT_COMMIT";

#[derive(Clone, Debug, Serialize)]
pub struct Machine {
    pub hostname: String,
    pub cpu: String,
    pub cpu_cores: usize,
}

#[derive(Clone, Debug, Serialize)]
pub struct Adapter {
    pub name: String,
    pub driver: String,
    pub driver_info: String,
    pub backend: String,
    pub device_type: String,
}

impl Machine {
    pub fn this() -> Machine {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let cpu = cpuinfo
            .lines()
            .find_map(|l| {
                l.strip_prefix("model name")?
                    .split_once(':')
                    .map(|(_, v)| v)
            })
            .map_or("unknown", str::trim)
            .to_string();
        Machine {
            hostname: read_trimmed("/proc/sys/kernel/hostname")
                .or_else(|| read_trimmed("/etc/hostname"))
                .unwrap_or_else(|| "unknown".into()),
            cpu,
            cpu_cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        }
    }
}

impl Adapter {
    pub fn of(gpu: &Gpu) -> Adapter {
        let info = &gpu.info;
        Adapter {
            name: info.name.clone(),
            driver: info.driver.clone(),
            driver_info: info.driver_info.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
        }
    }
}

/// `$RGRAPH_GIT_COMMIT`, else `git rev-parse HEAD` with "-dirty" appended when tracked
/// files differ from it (the binary may hold uncommitted work), else "unknown".
pub fn git_commit() -> String {
    let from_env = std::env::var(COMMIT_ENV)
        .ok()
        .filter(|c| !c.trim().is_empty());
    from_env
        .or_else(|| {
            let head = git(&["rev-parse", "HEAD"])?;
            let changed = git(&["status", "--porcelain", "--untracked-files=no"])?;
            Some(if changed.is_empty() {
                head
            } else {
                format!("{head}-dirty")
            })
        })
        .unwrap_or_else(|| "unknown".into())
}

/// What `git ARGS` prints, trimmed, when it succeeds.
fn git(args: &[&str]) -> Option<String> {
    let out = std::process::Command::new("git").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Now, in UTC, as RFC 3339 (`2026-11-23T09:41:07Z`).
pub fn timestamp() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let (year, month, day) = civil_from_days(days as i64);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rest / 3600,
        rest % 3600 / 60,
        rest % 60
    )
}

/// The proleptic Gregorian date `days` after 1970-01-01 (Howard Hinnant's algorithm).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

fn read_trimmed(path: &str) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    Some(text.trim().to_string()).filter(|t| !t.is_empty())
}

#[cfg(test)]
mod tests {
    use super::civil_from_days;

    #[test]
    fn dates_from_days() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(19_782), (2024, 2, 29));
        assert_eq!(civil_from_days(20_415), (2025, 11, 23));
    }
}
