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
}

impl ModeSelection {
    /// The indices kept, ascending, given all frequencies (Hz, ascending).
    pub fn select(&self, frequencies_hz: &[f64]) -> Result<Vec<usize>, ModelError> {
        let available = frequencies_hz.len();
        match self {
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
