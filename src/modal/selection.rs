//! Which modes of the reduced rod to keep.

use crate::error::ModelError;

/// Mode selection, applied to the modes sorted by frequency.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeSelection {
    /// The lowest `n` modes.
    Count(usize),
    /// Every mode with frequency at or below `max_hz`.
    Cutoff { max_hz: f64 },
    /// Modes by 0-based index into the sorted list, e.g. `[0, 1, 5]`.
    Indices(Vec<usize>),
    /// The lowest `count` modes, and then the lowest axial modes missing until at least
    /// `axial` of the kept ones are axial (none added when `count` is 0: the rigid rod). The
    /// selection of a scene's `rod.modes` and `rod.axial_modes`: modes of one frequency are
    /// kept or left out together (a `count` that splits them is refused, an axial mode comes
    /// with the modes of its frequency). The other selections keep what they name.
    CountWithAxial { count: usize, axial: usize },
    /// The lowest `bending` bending modes (with the modes of the last one's frequency; every
    /// bending mode where the rod has fewer, a refusal where it has fewer modes at all) and
    /// the lowest `axial` axial modes in addition: an axial mode below the highest kept
    /// bending mode never takes a bending mode's place, and the count stays at most
    /// `bending + axial` (plus equal-frequency partners).
    /// The selection where axial dynamics is switched on (`rod.axial_dynamics` `auto` or
    /// `on`): the axial mode joins the bending band the scene asked for.
    BendingWithAxial { bending: usize, axial: usize },
}

impl ModeSelection {
    /// [`Self::select`] with each mode's axial energy share (a mode is axial above 1/2), which
    /// [`ModeSelection::CountWithAxial`] needs.
    pub fn select_classified(
        &self,
        frequencies_hz: &[f64],
        axial_shares: &[f64],
    ) -> Result<Vec<usize>, ModelError> {
        let is_axial = |k: usize| axial_shares.get(k).is_some_and(|&s| s > 0.5);
        let (count, axial, mut kept) = match self {
            ModeSelection::CountWithAxial { count, axial } => {
                let kept = ModeSelection::Count(*count).select(frequencies_hz)?;
                check_whole_clusters(&kept, frequencies_hz)?;
                (count, axial, kept)
            }
            ModeSelection::BendingWithAxial { bending, axial } => {
                // The bending modes up to the `bending`-th and those of its frequency (every
                // bending mode where the rod has fewer); the axial modes come below.
                let available = frequencies_hz.len();
                if *bending > available {
                    return Err(ModelError::TooManyModes {
                        requested: *bending,
                        available,
                    });
                }
                let bending_modes: Vec<usize> = (0..available).filter(|&k| !is_axial(k)).collect();
                let end = match *bending {
                    0 => 0,
                    n => bending_modes
                        .get(n - 1)
                        .map_or(available, |&k| cluster(frequencies_hz, k).end),
                };
                // With the modes of each one's frequency (an axial mode of equal frequency
                // comes with its partner).
                let mut kept: Vec<usize> = Vec::new();
                for k in bending_modes.into_iter().filter(|&k| k < end) {
                    for j in cluster(frequencies_hz, k) {
                        if !kept.contains(&j) {
                            kept.push(j);
                        }
                    }
                }
                (bending, axial, kept)
            }
            _ => return self.select(frequencies_hz),
        };
        if *count == 0 {
            return Ok(kept);
        }
        let mut have = kept.iter().filter(|&&k| is_axial(k)).count();
        for k in 0..frequencies_hz.len() {
            if have >= *axial {
                break;
            }
            if is_axial(k) && !kept.contains(&k) {
                // The mode with the modes of its frequency ("at least" `axial` axial modes).
                for j in cluster(frequencies_hz, k) {
                    if !kept.contains(&j) {
                        kept.push(j);
                        have += usize::from(is_axial(j));
                    }
                }
            }
        }
        kept.sort_unstable();
        check_whole_clusters(&kept, frequencies_hz)?;
        Ok(kept)
    }

    /// The indices kept, ascending, given all frequencies (Hz, ascending).
    /// [`ModeSelection::CountWithAxial`] keeps the lowest `count` here (no shares).
    pub fn select(&self, frequencies_hz: &[f64]) -> Result<Vec<usize>, ModelError> {
        let available = frequencies_hz.len();
        match self {
            ModeSelection::CountWithAxial { count, .. }
            | ModeSelection::BendingWithAxial { bending: count, .. } => {
                ModeSelection::Count(*count).select(frequencies_hz)
            }
            ModeSelection::Count(n) => {
                if *n > available {
                    return Err(ModelError::TooManyModes {
                        requested: *n,
                        available,
                    });
                }
                Ok((0..*n).collect())
            }
            ModeSelection::Cutoff { max_hz } => {
                if max_hz.is_nan() || *max_hz < 0.0 {
                    return Err(ModelError::InvalidParameter {
                        name: "mode cutoff frequency",
                        value: *max_hz,
                        allowed: "a value >= 0 Hz (infinity keeps all)".into(),
                    });
                }
                Ok((0..available)
                    .filter(|&i| frequencies_hz[i] <= *max_hz)
                    .collect())
            }
            ModeSelection::Indices(list) => {
                let mut sorted = list.clone();
                sorted.sort_unstable();
                sorted.dedup();
                if sorted.len() != list.len() {
                    return Err(ModelError::ReferenceConditions {
                        message: format!("mode index list {list:?} repeats an index"),
                    });
                }
                if let Some(&bad) = sorted.iter().find(|&&i| i >= available) {
                    return Err(ModelError::InvalidInteger {
                        name: "mode index",
                        value: bad as i64,
                        allowed: format!("0..={}", available.saturating_sub(1)),
                    });
                }
                Ok(sorted)
            }
        }
    }
}

/// Relative difference below which two frequencies of the rod count as one (a multiple
/// eigenvalue computed to round-off: about `eps lambda_max / lambda`, 1e-7 at most at the
/// largest mesh).
pub const EQUAL_FREQUENCIES: f64 = 5e-6;

/// The indices of the modes whose frequency equals that of mode `k` (`frequencies_hz`
/// ascending), `k` among them.
fn cluster(frequencies_hz: &[f64], k: usize) -> std::ops::Range<usize> {
    let f = frequencies_hz[k];
    let equal = |g: f64| (g - f).abs() <= EQUAL_FREQUENCIES * f.abs().max(g.abs());
    let mut lo = k;
    while lo > 0 && equal(frequencies_hz[lo - 1]) {
        lo -= 1;
    }
    let mut hi = k + 1;
    while hi < frequencies_hz.len() && equal(frequencies_hz[hi]) {
        hi += 1;
    }
    lo..hi
}

/// Modes of one frequency are kept or left out together: any combination of them is a mode
/// too, so keeping some of them keeps an arbitrary shape (the rod clamped at its midpoint,
/// `body_fixed_mid`, has every frequency twice: its halves vibrate alike).
fn check_whole_clusters(kept: &[usize], frequencies_hz: &[f64]) -> Result<(), ModelError> {
    for &k in kept {
        let whole = cluster(frequencies_hz, k);
        if let Some(missing) = whole.clone().find(|j| !kept.contains(j)) {
            return Err(ModelError::InvalidInteger {
                name: "rod.modes",
                value: kept.len() as i64,
                allowed: format!(
                    "a selection that keeps modes of equal frequency together: modes {} to {} all have {:.6} Hz and mode {} is left out (with rod.reference = body_fixed_mid the two halves of the rod vibrate alike); e.g. rod.modes = {} or {}",
                    whole.start + 1,
                    whole.end,
                    frequencies_hz[k],
                    missing + 1,
                    whole.start,
                    whole.end
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `selection` keeps of modes of frequencies `f` and axial shares `shares`.
    fn picked(selection: ModeSelection, f: &[f64], shares: &[f64]) -> Vec<usize> {
        selection.select_classified(f, shares).unwrap()
    }

    #[test]
    fn axial_modes_are_added_after_the_count() {
        let f = [10.0, 20.0, 30.0, 40.0, 50.0];
        let shares = [0.0, 0.0, 0.0, 1.0, 0.9];
        let pick =
            |count, axial| picked(ModeSelection::CountWithAxial { count, axial }, &f, &shares);
        assert_eq!(pick(2, 0), vec![0, 1]);
        assert_eq!(pick(2, 1), vec![0, 1, 3]);
        assert_eq!(pick(2, 2), vec![0, 1, 3, 4]);
        assert_eq!(pick(4, 1), vec![0, 1, 2, 3]);
        // More axial modes than the rod has: all of them; the rigid rod stays rigid.
        assert_eq!(pick(1, 5), vec![0, 3, 4]);
        assert_eq!(pick(0, 1), Vec::<usize>::new());
    }

    #[test]
    fn axial_modes_join_the_bending_band() {
        let f = [10.0, 20.0, 30.0, 40.0, 50.0];
        let shares = [0.0, 0.9, 0.0, 0.0, 1.0];
        let pick = |bending, axial| {
            picked(
                ModeSelection::BendingWithAxial { bending, axial },
                &f,
                &shares,
            )
        };
        assert_eq!(pick(1, 1), vec![0, 1]);
        assert_eq!(pick(2, 1), vec![0, 1, 2]);
        assert_eq!(pick(3, 1), vec![0, 1, 2, 3]);
        assert_eq!(pick(3, 2), vec![0, 1, 2, 3, 4]);
        // More bending modes than the rod has: every bending mode; more than it has modes:
        // refused. Axial modes in the band beyond `axial` are left out.
        assert_eq!(pick(4, 1), vec![0, 1, 2, 3]);
        assert_eq!(pick(5, 1), vec![0, 1, 2, 3]);
        assert!(ModeSelection::BendingWithAxial {
            bending: 6,
            axial: 1
        }
        .select_classified(&f, &shares)
        .is_err());
        assert_eq!(pick(0, 1), Vec::<usize>::new());
        // The band ends with the modes of its last bending mode's frequency.
        let f = [10.0, 10.0, 20.0, 30.0, 30.0];
        let shares = [0.0, 0.0, 1.0, 0.0, 0.0];
        let pick = |bending, axial| {
            picked(
                ModeSelection::BendingWithAxial { bending, axial },
                &f,
                &shares,
            )
        };
        assert_eq!(pick(1, 1), vec![0, 1, 2]);
        assert_eq!(pick(3, 1), vec![0, 1, 2, 3, 4]);
        let f = [10.0, 20.0, 30.0, 40.0, 50.0];
        let shares = [0.0, 0.9, 0.0, 0.0, 1.0];
        // The lowest `count` modes of CountWithAxial take the axial mode in place of one.
        let count_with_axial = ModeSelection::CountWithAxial { count: 2, axial: 1 };
        assert_eq!(picked(count_with_axial, &f, &shares), vec![0, 1]);
    }

    #[test]
    fn equal_frequencies_stay_together() {
        let f = [10.0, 10.0, 20.0, 20.0 * (1.0 + 1e-7), 30.0];
        let shares = [0.0, 0.0, 1.0, 1.0, 0.0];
        let count =
            |n| ModeSelection::CountWithAxial { count: n, axial: 0 }.select_classified(&f, &shares);
        assert_eq!(count(2).unwrap(), vec![0, 1]);
        assert_eq!(count(4).unwrap(), vec![0, 1, 2, 3]);
        for n in [1, 3] {
            let text = count(n).unwrap_err().to_string();
            assert!(
                text.contains("rod.modes") && text.contains("equal frequency"),
                "{text}"
            );
        }
        // The library's own count keeps what it names.
        assert_eq!(
            ModeSelection::Count(3)
                .select_classified(&f, &shares)
                .unwrap(),
            vec![0, 1, 2]
        );
        // An axial mode added by CountWithAxial brings its partner.
        let pick = ModeSelection::CountWithAxial { count: 2, axial: 1 }
            .select_classified(&f, &shares)
            .unwrap();
        assert_eq!(pick, vec![0, 1, 2, 3]);
    }

    #[test]
    fn selections() {
        let f = [10.0, 20.0, 30.0];
        assert_eq!(ModeSelection::Count(2).select(&f).unwrap(), vec![0, 1]);
        assert_eq!(
            ModeSelection::Cutoff { max_hz: 25.0 }.select(&f).unwrap(),
            vec![0, 1]
        );
        assert_eq!(
            ModeSelection::Indices(vec![2, 0]).select(&f).unwrap(),
            vec![0, 2]
        );
        assert!(matches!(
            ModeSelection::Count(4).select(&f),
            Err(ModelError::TooManyModes {
                requested: 4,
                available: 3
            })
        ));
        assert!(ModeSelection::Indices(vec![3]).select(&f).is_err());
        assert!(ModeSelection::Indices(vec![1, 1]).select(&f).is_err());
    }
}
