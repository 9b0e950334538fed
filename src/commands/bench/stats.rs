//! Median and spread of a figure over the measured frames.

use serde::Serialize;

/// Milliseconds over the measured frames: the median, and the 10th and 90th percentiles
/// and extremes as the spread (percentiles by nearest rank, so every value is one that
/// was measured).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Spread {
    pub median: f64,
    pub p10: f64,
    pub p90: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// The spread of `ns` (nanoseconds) in milliseconds; `None` when there is no value.
    pub fn of_ns(ns: impl IntoIterator<Item = u64>) -> Option<Spread> {
        let mut ms: Vec<f64> = ns.into_iter().map(|n| n as f64 / 1e6).collect();
        if ms.is_empty() {
            return None;
        }
        ms.sort_by(f64::total_cmp);
        let rank = |q: f64| ms[((q * ms.len() as f64).ceil() as usize).clamp(1, ms.len()) - 1];
        let mid = ms.len() / 2;
        let median = if ms.len() % 2 == 1 {
            ms[mid]
        } else {
            (ms[mid - 1] + ms[mid]) / 2.0
        };
        Some(Spread {
            median,
            p10: rank(0.1),
            p90: rank(0.9),
            min: ms[0],
            max: ms[ms.len() - 1],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Spread;

    #[test]
    fn median_and_percentiles_by_nearest_rank() {
        let s = Spread::of_ns((1..=10).map(|i| i * 1_000_000)).unwrap();
        assert_eq!(
            (s.median, s.p10, s.p90, s.min, s.max),
            (5.5, 1.0, 9.0, 1.0, 10.0)
        );
        let one = Spread::of_ns([2_000_000]).unwrap();
        assert_eq!((one.median, one.p10, one.p90), (2.0, 2.0, 2.0));
        assert!(Spread::of_ns([]).is_none());
    }
}
