//! A section that varies along the rod: a table of stations, properties linear between
//! consecutive stations (scene table `[[rod.section]]`, `docs/fmu.md`,
//! "Real connecting rods"), and the rigid bodies attached at the ends (`[rod.big_end]`,
//! `[rod.small_end]`).
//!
//! Stations are given by their arc length `position` from B (m). Two stations may share a
//! position: the section then steps there (a stepped rod); the value at the step itself is the
//! later station's. Element integrals never evaluate a property at a station: they split the
//! element at the stations inside it ([`SectionTable::pieces`]), so each piece's integrand is a
//! polynomial and Gauss quadrature is exact.

use serde::{Deserialize, Serialize};

use crate::error::ModelError;

/// Default shear area, as a fraction of the area: `A_s = A / 1.2` (shear coefficient 5/6 of a
/// rectangular section; Cowper 1966, "The shear coefficient in Timoshenko's beam theory",
/// J. Appl. Mech. 33, for Poisson's ratio 0).
pub const DEFAULT_SHEAR_AREA_FACTOR: f64 = 1.0 / 1.2;

/// One station of the table (scene `[[rod.section]]`). SI units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionStation {
    /// Arc length from B, m.
    pub position: f64,
    /// Cross-section area A, m^2.
    pub area: f64,
    /// Second moment of area I (bending in the mechanism's plane), m^4.
    pub area_moment: f64,
    /// Shear area A_s = k A, m^2 (default `A / 1.2`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_area: Option<f64>,
    /// Distance of the outer fibre from the neutral axis, m (needed for stress only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fibre_distance: Option<f64>,
}

/// Section properties at one arc length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionValues {
    /// A, m^2.
    pub area: f64,
    /// I, m^4.
    pub area_moment: f64,
    /// A_s, m^2.
    pub shear_area: f64,
    /// c, m (None when a neighbouring station does not give it).
    pub fibre_distance: Option<f64>,
}

/// A rigid body attached at one end of the rod: a point mass at the end and a rotary inertia
/// about the end (scene `[rod.big_end]` at B, `[rod.small_end]` at C).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EndBody {
    /// Mass, kg.
    #[serde(default)]
    pub mass: f64,
    /// Rotary inertia about the rod's end point, kg m^2.
    #[serde(default)]
    pub inertia: f64,
}

impl EndBody {
    /// Both values finite and >= 0; `name` is `rod.big_end` or `rod.small_end`.
    pub fn validate(&self, which: End) -> Result<(), ModelError> {
        let (mass_name, inertia_name) = match which {
            End::B => ("rod.big_end.mass", "rod.big_end.inertia"),
            End::C => ("rod.small_end.mass", "rod.small_end.inertia"),
        };
        // Windows as the slider's: up to 1e6 kg and 1e6 kg m^2.
        crate::error::require_within(mass_name, self.mass, 0.0, 1e6, "kg")?;
        crate::error::require_within(inertia_name, self.inertia, 0.0, 1e6, "kg m^2")
    }

    /// Whether the body has no mass and no inertia.
    pub fn is_empty(&self) -> bool {
        self.mass == 0.0 && self.inertia == 0.0
    }
}

/// Which end of the rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// The crank-pin end, arc length 0.
    B,
    /// The slider-pin end, arc length L.
    C,
}

/// Most `[[rod.section]]` stations a table may have. The model's preprocessing grows steeply
/// with the station count; at this many the initialization of the largest model stays within
/// the time docs/fmu.md states for the declared maxima (`tests/work_bound.rs`).
pub const MAX_STATIONS: usize = 256;

/// Refuse a table of more than [`MAX_STATIONS`] stations (before anything is built from it).
pub fn check_station_count(count: usize) -> Result<(), ModelError> {
    if count > MAX_STATIONS {
        return Err(ModelError::InvalidInteger {
            name: "rod.section",
            value: count as i64,
            allowed: format!("at most {MAX_STATIONS} [[rod.section]] stations"),
        });
    }
    Ok(())
}

/// A validated station table over `[0, length]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionTable {
    length: f64,
    stations: Vec<SectionStation>,
}

fn station_error(
    field: &'static str,
    index: usize,
    st: &SectionStation,
    value: f64,
    what: &str,
) -> ModelError {
    ModelError::InvalidParameter {
        name: field,
        value,
        allowed: format!(
            "{what} (station {index} of [[rod.section]], counted from 0, position {} m)",
            st.position
        ),
    }
}

impl SectionTable {
    /// Validate a table for a rod of `length` m. Rules (each error names the station and value):
    /// positions finite and non-decreasing, at most two stations at one position (a step); the
    /// first at 0 and the last at `length` (both within `1e-9 length`, then set exactly); a
    /// single station means a constant section and must sit at 0; area, area moment, shear
    /// area and fibre distance finite and > 0 where given.
    pub fn new(length: f64, stations: &[SectionStation]) -> Result<SectionTable, ModelError> {
        crate::error::require_positive("rod.length", length)?;
        check_station_count(stations.len())?;
        if stations.is_empty() {
            return Err(ModelError::InvalidParameter {
                name: "rod.section",
                value: 0.0,
                allowed: "at least one [[rod.section]] station".into(),
            });
        }
        let tol = 1e-9 * length;
        for (i, st) in stations.iter().enumerate() {
            if !st.position.is_finite() {
                return Err(station_error(
                    "rod.section.position",
                    i,
                    st,
                    st.position,
                    "a finite position",
                ));
            }
            let positive = |name: &'static str, v: f64| {
                if v.is_finite() && v > 0.0 {
                    Ok(())
                } else {
                    Err(station_error(name, i, st, v, "a finite value > 0"))
                }
            };
            positive("rod.section.area", st.area)?;
            positive("rod.section.area_moment", st.area_moment)?;
            if let Some(a) = st.shear_area {
                positive("rod.section.shear_area", a)?;
            }
            if let Some(c) = st.fibre_distance {
                positive("rod.section.fibre_distance", c)?;
            }
            if i > 0 {
                let prev = stations[i - 1].position;
                if st.position < prev {
                    return Err(station_error(
                        "rod.section.position",
                        i,
                        st,
                        st.position,
                        &format!("a position >= the previous station's {prev} m (stations in order from B)"),
                    ));
                }
                if i > 1 && st.position == prev && stations[i - 2].position == prev {
                    return Err(station_error(
                        "rod.section.position",
                        i,
                        st,
                        st.position,
                        "at most two stations at one position (a step)",
                    ));
                }
            }
        }
        let first = &stations[0];
        if first.position.abs() > tol {
            return Err(station_error(
                "rod.section.position",
                0,
                first,
                first.position,
                "0 for the first station (the table must start at B)",
            ));
        }
        let n = stations.len();
        let last = &stations[n - 1];
        if n > 1 && (last.position - length).abs() > tol {
            return Err(station_error(
                "rod.section.position",
                n - 1,
                last,
                last.position,
                &format!("rod.length = {length} m for the last station (the table must reach C)"),
            ));
        }
        let mut stations = stations.to_vec();
        stations[0].position = 0.0;
        if n > 1 {
            stations[n - 1].position = length;
        }
        Ok(SectionTable { length, stations })
    }

    /// The one-station table of a uniform section.
    pub fn uniform(length: f64, area: f64, area_moment: f64) -> SectionTable {
        SectionTable {
            length,
            stations: vec![SectionStation {
                position: 0.0,
                area,
                area_moment,
                shear_area: None,
                fibre_distance: None,
            }],
        }
    }

    /// The same table with the shear area `shear_area` (m^2) at every station (`None`: each
    /// station's own, default `A / 1.2`).
    pub fn with_uniform_shear_area(mut self, shear_area: Option<f64>) -> SectionTable {
        if shear_area.is_some() {
            for st in &mut self.stations {
                st.shear_area = shear_area;
            }
        }
        self
    }

    /// Rod length, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The stations.
    pub fn stations(&self) -> &[SectionStation] {
        &self.stations
    }

    /// Whether the section is the same everywhere (one station, or all stations equal).
    pub fn is_uniform(&self) -> bool {
        let s0 = &self.stations[0];
        self.stations.iter().all(|s| {
            s.area == s0.area
                && s.area_moment == s0.area_moment
                && s.shear_area == s0.shear_area
                && s.fibre_distance == s0.fibre_distance
        })
    }

    fn values(st: &SectionStation) -> SectionValues {
        SectionValues {
            area: st.area,
            area_moment: st.area_moment,
            shear_area: st.shear_area.unwrap_or(st.area * DEFAULT_SHEAR_AREA_FACTOR),
            fibre_distance: st.fibre_distance,
        }
    }

    /// The physical windows of the uniform rod (`PHYSICAL_RANGES` of area and area moment),
    /// per station, and the radius of gyration at most the rod length; the error names the
    /// station.
    pub fn validate_physical(&self) -> Result<(), ModelError> {
        let [_, _, _, area, moment] = super::section::PHYSICAL_RANGES;
        let length = self.length();
        for (i, st) in self.stations.iter().enumerate() {
            for (name, v, (lo, hi), unit) in [
                ("rod.section.area", st.area, area, "m^2"),
                ("rod.section.area_moment", st.area_moment, moment, "m^4"),
            ] {
                if !(lo..=hi).contains(&v) {
                    let allowed = format!("a value in [{lo:e}, {hi:e}] {unit}");
                    return Err(station_error(name, i, st, v, &allowed));
                }
            }
            if st.area_moment > st.area * length * length {
                let allowed = format!(
                    "at most area * rod.length^2 = {:e} m^4 (radius of gyration at most the rod length)",
                    st.area * length * length
                );
                return Err(station_error(
                    "rod.section.area_moment",
                    i,
                    st,
                    st.area_moment,
                    &allowed,
                ));
            }
        }
        Ok(())
    }

    /// Properties at arc length `s` (clamped to `[0, L]`): linear between stations; at a step
    /// the later station's values.
    pub fn at(&self, s: f64) -> SectionValues {
        let s = s.clamp(0.0, self.length);
        self.interpolate(self.interval(s), s)
    }

    /// The index `i` of the last station interval `[p_i, p_{i+1}]` with `p_i <= s` and
    /// `p_i < p_{i+1}` (0 for a one-station table).
    fn interval(&self, s: f64) -> usize {
        let st = &self.stations;
        let mut i = 0;
        for k in 0..st.len().saturating_sub(1) {
            if st[k].position <= s && st[k + 1].position > st[k].position {
                i = k;
            }
        }
        i
    }

    /// The linear interpolation of interval `i` evaluated at `s` (may be its end points).
    fn interpolate(&self, i: usize, s: f64) -> SectionValues {
        let st = &self.stations;
        if st.len() == 1 {
            return Self::values(&st[0]);
        }
        let (a, b) = (&st[i], &st[i + 1]);
        let t = ((s - a.position) / (b.position - a.position)).clamp(0.0, 1.0);
        let (va, vb) = (Self::values(a), Self::values(b));
        let lerp = |x: f64, y: f64| x + t * (y - x);
        SectionValues {
            area: lerp(va.area, vb.area),
            area_moment: lerp(va.area_moment, vb.area_moment),
            shear_area: lerp(va.shear_area, vb.shear_area),
            fibre_distance: match (va.fibre_distance, vb.fibre_distance) {
                (Some(x), Some(y)) => Some(lerp(x, y)),
                _ => None,
            },
        }
    }

    /// The values at both ends of a piece `(p0, p1)` from [`Self::pieces`], taken from the
    /// linear interpolation the piece lies in (so a step at an end does not leak in).
    pub fn piece_ends(&self, p0: f64, p1: f64) -> (SectionValues, SectionValues) {
        let i = self.interval(0.5 * (p0 + p1));
        (self.interpolate(i, p0), self.interpolate(i, p1))
    }

    /// `[a, b]` cut at the station positions strictly inside it: the pieces on which every
    /// property is linear.
    pub fn pieces(&self, a: f64, b: f64) -> Vec<(f64, f64)> {
        let mut cuts = vec![a];
        for st in &self.stations {
            if st.position > a && st.position < b && Some(&st.position) != cuts.last() {
                cuts.push(st.position);
            }
        }
        cuts.push(b);
        cuts.windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// `int_a^b f(s, section(s)) ds` for an `f` polynomial of degree <= 7 on each piece, by
    /// 4-point Gauss-Legendre quadrature on each piece (Abramowitz and Stegun 25.4.30; a
    /// property linear in `s` times a product of two cubic shape functions is degree 7).
    pub fn integrate<T, F>(&self, a: f64, b: f64, zero: T, mut f: F) -> T
    where
        T: std::ops::AddAssign,
        F: FnMut(f64, SectionValues, f64) -> T,
    {
        let mut acc = zero;
        for (s, v, w) in self.quadrature_points(a, b) {
            acc += f(s, v, w);
        }
        acc
    }

    /// The quadrature points of [`Self::integrate`]: `(s, section(s), weight ds)`.
    pub fn quadrature_points(&self, a: f64, b: f64) -> Vec<(f64, SectionValues, f64)> {
        let mut points = Vec::new();
        for (p0, p1) in self.pieces(a, b) {
            let h = p1 - p0;
            let i = self.interval(0.5 * (p0 + p1));
            for (xi, w) in super::quadrature::GAUSS4 {
                let s = p0 + xi * h;
                points.push((s, self.interpolate(i, s), w * h));
            }
        }
        points
    }

    /// `(int_s^L A ds', int_s^L A s' ds')`, m^3 and m^4, exactly (trapezoid and Simpson rules
    /// on the linear pieces).
    pub fn tail_integrals(&self, s: f64) -> (f64, f64) {
        let mut area = 0.0;
        let mut moment = 0.0;
        for (p0, p1) in self.pieces(s, self.length) {
            let h = p1 - p0;
            let (v0, v1) = self.piece_ends(p0, p1);
            let (a0, a1) = (v0.area, v1.area);
            let am = 0.5 * (a0 + a1);
            area += 0.5 * h * (a0 + a1);
            moment += h / 6.0 * (a0 * p0 + 4.0 * am * 0.5 * (p0 + p1) + a1 * p1);
        }
        (area, moment)
    }

    /// `int_a^b ds / f(section(s))` for a property `f` linear between stations (e.g. the area
    /// moment, giving m^-3), exactly: `h ln(f_1 / f_0) / (f_1 - f_0)` on each linear piece.
    pub fn compliance_integral<F>(&self, a: f64, b: f64, f: F) -> f64
    where
        F: Fn(&SectionValues) -> f64,
    {
        let mut total = 0.0;
        for (p0, p1) in self.pieces(a, b) {
            let h = p1 - p0;
            if h <= 0.0 {
                continue;
            }
            let (v0, v1) = self.piece_ends(p0, p1);
            let (i0, i1) = (f(&v0), f(&v1));
            let r = i1 / i0;
            total += if (r - 1.0).abs() < 1e-8 {
                // Series of ln(r) / (r - 1) about r = 1.
                let d = r - 1.0;
                h / i0 * (1.0 - d / 2.0 + d * d / 3.0)
            } else {
                h * r.ln() / (i1 - i0)
            };
        }
        total
    }

    /// Check that every station gives a fibre distance (stress needs `c(s)` everywhere); the
    /// error names the first station without one.
    pub fn require_fibre_distance(&self) -> Result<(), ModelError> {
        for (i, st) in self.stations.iter().enumerate() {
            if st.fibre_distance.is_none() {
                return Err(station_error(
                    "rod.section.fibre_distance",
                    i,
                    st,
                    f64::NAN,
                    "a fibre distance > 0 at every station when stress is asked for",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "section_table_tests.rs"]
mod tests;
