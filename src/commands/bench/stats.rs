//! A figure measured in interleaved rounds: each round's median over its frames, then
//! the median of those round medians and their spread.

use serde::Serialize;

/// Milliseconds measured over rounds of frames. `median` is the median of the round
/// medians (each round's median over its frames); `p10`, `p90`, `min` and `max` are
/// taken over the round medians too (percentiles by nearest rank, so every value is a
/// round median that was measured: with 9 rounds or fewer p10 is the fastest round and
/// p90 the slowest), and `spread` is `(p90 - p10) / median`, the share of the figure a
/// reader cannot trust.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Spread {
    pub median: f64,
    pub p10: f64,
    pub p90: f64,
    pub min: f64,
    pub max: f64,
    /// `(p90 - p10) / median`: 0.05 is a spread of 5% (0 when the median is 0).
    pub spread: f64,
    /// Each round's median, in the order the rounds ran.
    pub rounds: Vec<f64>,
}

impl Spread {
    /// The spread of `rounds`, each a round's values in nanoseconds, in milliseconds;
    /// rounds without a value are left out, and `None` when no round has one.
    pub fn of_rounds<R, I>(rounds: R) -> Option<Spread>
    where
        R: IntoIterator<Item = I>,
        I: IntoIterator<Item = u64>,
    {
        let medians: Vec<f64> = rounds
            .into_iter()
            .filter_map(|round| median(round.into_iter().map(|n| n as f64 / 1e6).collect()))
            .collect();
        let mut sorted = medians.clone();
        sorted.sort_by(f64::total_cmp);
        let rank =
            |q: f64| sorted[((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len()) - 1];
        let middle = median(sorted.clone())?;
        let (p10, p90) = (rank(0.1), rank(0.9));
        Some(Spread {
            median: middle,
            p10,
            p90,
            min: sorted[0],
            max: sorted[sorted.len() - 1],
            spread: relative(p90 - p10, middle),
            rounds: medians,
        })
    }
}

/// The median of `values` (the mean of the middle two for an even count); `None` when
/// empty.
pub fn median(mut values: Vec<f64>) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    let mid = values.len() / 2;
    Some(match values.len() % 2 {
        1 => values[mid],
        _ => (values[mid - 1] + values[mid]) / 2.0,
    })
}

/// `part / whole`, 0 when `whole` is 0.
pub fn relative(part: f64, whole: f64) -> f64 {
    if whole > 0.0 {
        part / whole
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::Spread;

    const MS: u64 = 1_000_000;

    #[test]
    fn the_median_of_round_medians() {
        // Every round has one 100 ms frame, which no round median sees: the round medians
        // are 2, 4, 6, 8 and 10 and the row's time 6, where the median of all fifteen
        // frames would be 8.
        let rounds = [
            [1, 2, 100],
            [3, 4, 100],
            [5, 6, 100],
            [7, 8, 100],
            [9, 10, 100],
        ]
        .map(|r| r.map(|v| v * MS));
        let s = Spread::of_rounds(rounds).unwrap();
        assert_eq!(s.rounds, [2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!((s.median, s.min, s.max), (6.0, 2.0, 10.0));
        // Five rounds: nearest rank makes p10 the fastest and p90 the slowest.
        assert_eq!((s.p10, s.p90), (2.0, 10.0));
        assert_eq!(s.spread, 8.0 / 6.0);
        // A round of an even count of frames has the mean of its middle two as median.
        let even = Spread::of_rounds([[4 * MS, 6 * MS, MS, 9 * MS]]).unwrap();
        assert_eq!(even.rounds, [5.0]);
    }

    #[test]
    fn percentiles_by_nearest_rank_over_ten_rounds() {
        let s = Spread::of_rounds((1..=10).map(|i| [i * MS])).unwrap();
        assert_eq!(
            (s.median, s.p10, s.p90, s.min, s.max),
            (5.5, 1.0, 9.0, 1.0, 10.0)
        );
        let one = Spread::of_rounds([[2 * MS]]).unwrap();
        assert_eq!(
            (one.median, one.p10, one.p90, one.spread),
            (2.0, 2.0, 2.0, 0.0)
        );
    }

    #[test]
    fn rounds_without_values_are_left_out() {
        let s = Spread::of_rounds([vec![], vec![3 * MS], vec![]]).unwrap();
        assert_eq!(s.rounds, [3.0]);
        assert!(Spread::of_rounds([Vec::<u64>::new()]).is_none());
        assert!(Spread::of_rounds(Vec::<Vec<u64>>::new()).is_none());
    }
}
