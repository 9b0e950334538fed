//! Rows a reader should not trust as they stand: those whose GPU frame time spread over
//! more than [`SPREAD_LIMIT`] between rounds, each with the reasons the bench knows of.

use serde::Serialize;

use super::clocks::ClockSample;
use super::stats::{median, relative, Spread};

/// The largest `(p90 - p10) / median` of the round medians a row may have unflagged.
pub const SPREAD_LIMIT: f64 = 0.05;
/// SM clocks differing by more than this share between a row's rounds changed.
const CLOCK_CHANGE: f64 = 0.02;
/// Throttle reasons that slow the GPU for heat (or a hardware slowdown, which heat and
/// power draw both cause).
const THERMAL: [&str; 4] = [
    "sw_thermal_slowdown",
    "hw_thermal_slowdown",
    "hw_slowdown",
    "hw_power_brake_slowdown",
];
const POWER_CAP: &str = "sw_power_cap";

/// Why a row's rounds disagree, as far as the bench can tell.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Flag {
    /// The row's spread, as its `gpu_frame_ms.spread`.
    pub spread: f64,
    /// Empty when no reason is known.
    pub reasons: Vec<Reason>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reason {
    pub kind: ReasonKind,
    /// What was seen, for a person.
    pub detail: String,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ReasonKind {
    /// Pipelines or shader modules were created inside measured frames.
    FirstUseCompile,
    /// The SM clock differed between the row's rounds.
    ClocksChanged,
    /// A thermal or hardware slowdown was active in a round.
    Thermal,
    /// The software power cap held the clocks in a round.
    PowerCap,
    /// One round alone is out of line: without it the others agree.
    OutlierRound,
}

/// Device objects a pipeline's measured frames of one round created: its first use
/// inside the measurement (no warmup, or objects created late).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Created {
    /// The round, from 1.
    pub round: u32,
    pub render_pipelines: i64,
    pub compute_pipelines: i64,
    pub shader_modules: i64,
}

/// What is known about the rounds a row's time came from.
pub struct Evidence<'a> {
    pub time: &'a Spread,
    /// Objects created inside measured frames, per round that created any.
    pub created: &'a [Created],
    /// The clock sample of each round the row ran in (`None` where not reported).
    pub clocks: &'a [Option<ClockSample>],
}

/// The flag of a row whose spread exceeds [`SPREAD_LIMIT`], with every reason that
/// holds; `None` for a row within it.
pub fn judge(evidence: &Evidence) -> Option<Flag> {
    let time = evidence.time;
    if time.spread <= SPREAD_LIMIT {
        return None;
    }
    let reasons = [
        first_use(evidence.created),
        clocks_changed(evidence.clocks),
        throttled(
            evidence.clocks,
            &THERMAL,
            ReasonKind::Thermal,
            "thermal or hardware slowdown",
        ),
        throttled(
            evidence.clocks,
            &[POWER_CAP],
            ReasonKind::PowerCap,
            "power cap",
        ),
        outlier_round(&time.rounds),
    ];
    Some(Flag {
        spread: time.spread,
        reasons: reasons.into_iter().flatten().collect(),
    })
}

fn first_use(created: &[Created]) -> Option<Reason> {
    let first = created.first()?;
    Some(Reason {
        kind: ReasonKind::FirstUseCompile,
        detail: format!(
            "first-use compile: round {}'s frames created {} render and {} compute \
             pipelines and {} shader modules (raise --warmup)",
            first.round, first.render_pipelines, first.compute_pipelines, first.shader_modules
        ),
    })
}

fn clocks_changed(clocks: &[Option<ClockSample>]) -> Option<Reason> {
    let sm: Vec<u32> = clocks.iter().flatten().filter_map(|c| c.sm_mhz).collect();
    let (low, high) = (*sm.iter().min()?, *sm.iter().max()?);
    (relative(f64::from(high - low), f64::from(high)) > CLOCK_CHANGE).then(|| Reason {
        kind: ReasonKind::ClocksChanged,
        detail: format!("GPU clocks changed: SM {low}–{high} MHz across the rounds"),
    })
}

/// The rounds whose samples show any of `names` among the throttle reasons.
fn throttled(
    clocks: &[Option<ClockSample>],
    names: &[&str],
    kind: ReasonKind,
    what: &str,
) -> Option<Reason> {
    let rounds: Vec<String> = clocks
        .iter()
        .enumerate()
        .filter_map(|(i, c)| {
            let hit: Vec<&str> = c
                .as_ref()?
                .throttle
                .iter()
                .copied()
                .filter(|t| names.contains(t))
                .collect();
            (!hit.is_empty()).then(|| format!("round {} ({})", i + 1, hit.join(", ")))
        })
        .collect();
    (!rounds.is_empty()).then(|| Reason {
        kind,
        detail: format!("{what} in {}", rounds.join(", ")),
    })
}

/// The round that alone breaks the limit: with at least three rounds, the slowest or
/// the fastest, when the others' spread without it is within [`SPREAD_LIMIT`].
fn outlier_round(rounds: &[f64]) -> Option<Reason> {
    if rounds.len() < 3 {
        return None;
    }
    let by = |pick: fn(f64, f64) -> bool| {
        (0..rounds.len()).reduce(|a, b| if pick(rounds[b], rounds[a]) { b } else { a })
    };
    let slowest = by(|b, a| b > a)?;
    let fastest = by(|b, a| b < a)?;
    [(slowest, "slow"), (fastest, "fast")]
        .into_iter()
        .find_map(|(out, how)| {
            let others: Vec<f64> = rounds
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != out)
                .map(|(_, v)| *v)
                .collect();
            let rest = Spread::of_rounds(others.iter().map(|ms| [(ms * 1e6) as u64]))?;
            let middle = median(others)?;
            (rest.spread <= SPREAD_LIMIT).then(|| Reason {
                kind: ReasonKind::OutlierRound,
                detail: format!(
                    "a {how} outlier round: round {} took {:.3} ms, the others {:.3} ms \
                     (within {:.1}%)",
                    out + 1,
                    rounds[out],
                    middle,
                    rest.spread * 100.0
                ),
            })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: f64 = 1e6;

    fn rounds_of(round_ms: &[f64]) -> Spread {
        Spread::of_rounds(round_ms.iter().map(|ms| [(ms * MS) as u64])).unwrap()
    }

    fn sample(sm: u32, throttle: Vec<&'static str>) -> Option<ClockSample> {
        Some(ClockSample {
            sm_mhz: Some(sm),
            mem_mhz: Some(2619),
            throttle_reasons: "0x0".into(),
            throttle,
            temperature_c: Some(40),
        })
    }

    fn kinds(flag: &Flag) -> Vec<ReasonKind> {
        flag.reasons.iter().map(|r| r.kind).collect()
    }

    #[test]
    fn a_fake_slow_round_is_flagged_and_named() {
        let time = rounds_of(&[6.0, 6.02, 9.0, 5.99, 6.01]);
        let clocks = vec![sample(1980, vec!["gpu_idle"]); 5];
        let evidence = Evidence {
            time: &time,
            created: &[],
            clocks: &clocks,
        };
        let flag = judge(&evidence).expect("a slow round spreads the row by 50%");
        assert!((flag.spread - 3.01 / 6.01).abs() < 1e-9, "{flag:?}");
        assert_eq!(kinds(&flag), [ReasonKind::OutlierRound]);
        assert!(
            flag.reasons[0]
                .detail
                .starts_with("a slow outlier round: round 3 took 9.000 ms"),
            "{flag:?}"
        );
    }

    #[test]
    fn steady_rounds_are_not_flagged() {
        let time = rounds_of(&[6.0, 6.1, 6.05, 5.95, 6.0]);
        let clocks = [
            sample(1980, vec![]),
            sample(1410, vec!["hw_thermal_slowdown"]),
        ];
        let created = [Created {
            round: 1,
            render_pipelines: 3,
            compute_pipelines: 1,
            shader_modules: 2,
        }];
        let evidence = Evidence {
            time: &time,
            created: &created,
            clocks: &clocks,
        };
        // Within 5% whatever else was seen.
        assert_eq!(judge(&evidence), None);
    }

    #[test]
    fn clocks_heat_and_first_use_are_reasons() {
        // Rounds all over the place: no single outlier.
        let time = rounds_of(&[6.0, 9.0, 12.0, 7.5, 10.5]);
        let clocks = [
            sample(1980, vec![]),
            sample(1410, vec!["sw_thermal_slowdown", "gpu_idle"]),
            None,
            sample(1965, vec!["sw_power_cap"]),
            sample(1980, vec![]),
        ];
        let created = [Created {
            round: 1,
            render_pipelines: 3,
            compute_pipelines: 1,
            shader_modules: 2,
        }];
        let evidence = Evidence {
            time: &time,
            created: &created,
            clocks: &clocks,
        };
        let flag = judge(&evidence).unwrap();
        assert_eq!(
            kinds(&flag),
            [
                ReasonKind::FirstUseCompile,
                ReasonKind::ClocksChanged,
                ReasonKind::Thermal,
                ReasonKind::PowerCap
            ]
        );
        let details: Vec<&str> = flag.reasons.iter().map(|r| r.detail.as_str()).collect();
        assert_eq!(
            details[1..],
            [
                "GPU clocks changed: SM 1410–1980 MHz across the rounds",
                "thermal or hardware slowdown in round 2 (sw_thermal_slowdown)",
                "power cap in round 4 (sw_power_cap)"
            ]
        );
    }

    #[test]
    fn a_wide_row_without_a_known_cause_has_no_reason() {
        let time = rounds_of(&[6.0, 9.0, 12.0]);
        let flag = judge(&Evidence {
            time: &time,
            created: &[],
            clocks: &[None, None, None],
        })
        .unwrap();
        assert!(flag.reasons.is_empty(), "{flag:?}");
        // Two rounds cannot tell which one is out of line.
        let two = rounds_of(&[6.0, 9.0]);
        assert!(outlier_round(&two.rounds).is_none());
    }
}
