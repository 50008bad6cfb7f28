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
    /// `axial` of the kept ones are axial (none added when `count` is 0: the rigid rod).
    CountWithAxial { count: usize, axial: usize },
}

impl ModeSelection {
    /// [`Self::select`] with each mode's axial energy share (a mode is axial above 1/2), which
    /// [`ModeSelection::CountWithAxial`] needs.
    pub fn select_classified(
        &self,
        frequencies_hz: &[f64],
        axial_shares: &[f64],
    ) -> Result<Vec<usize>, ModelError> {
        let ModeSelection::CountWithAxial { count, axial } = self else {
            return self.select(frequencies_hz);
        };
        let mut kept = ModeSelection::Count(*count).select(frequencies_hz)?;
        if *count == 0 {
            return Ok(kept);
        }
        let is_axial = |k: usize| axial_shares.get(k).is_some_and(|&s| s > 0.5);
        let mut have = kept.iter().filter(|&&k| is_axial(k)).count();
        for k in *count..frequencies_hz.len() {
            if have >= *axial {
                break;
            }
            if is_axial(k) {
                kept.push(k);
                have += 1;
            }
        }
        Ok(kept)
    }

    /// The indices kept, ascending, given all frequencies (Hz, ascending).
    /// [`ModeSelection::CountWithAxial`] keeps the lowest `count` here (no shares).
    pub fn select(&self, frequencies_hz: &[f64]) -> Result<Vec<usize>, ModelError> {
        let available = frequencies_hz.len();
        match self {
            ModeSelection::CountWithAxial { count, .. } => {
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
                    return Err(ModelError::InvalidParameter {
                        name: "mode index",
                        value: bad as f64,
                        allowed: format!("0..={}", available.saturating_sub(1)),
                    });
                }
                Ok(sorted)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axial_modes_are_added_after_the_count() {
        let f = [10.0, 20.0, 30.0, 40.0, 50.0];
        let shares = [0.0, 0.0, 0.0, 1.0, 0.9];
        let pick = |count, axial| {
            ModeSelection::CountWithAxial { count, axial }
                .select_classified(&f, &shares)
                .unwrap()
        };
        assert_eq!(pick(2, 0), vec![0, 1]);
        assert_eq!(pick(2, 1), vec![0, 1, 3]);
        assert_eq!(pick(2, 2), vec![0, 1, 3, 4]);
        assert_eq!(pick(4, 1), vec![0, 1, 2, 3]);
        // More axial modes than the rod has: all of them; the rigid rod stays rigid.
        assert_eq!(pick(1, 5), vec![0, 3, 4]);
        assert_eq!(pick(0, 1), Vec::<usize>::new());
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
