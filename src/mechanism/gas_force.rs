//! A force on the slider given as a function of the crank angle (scene table
//! `[slider.gas_force]`): the cylinder gas force of an engine or a compressor over its cycle.
//!
//! The table's points `(angle_i, force_i)` (degrees of crank angle within one cycle of
//! `cycle` degrees: 720 for a four-stroke engine, 360 for a two-stroke engine or a compressor;
//! N along +x, negative towards the crank) are joined by the periodic cubic spline, continuous
//! with its first and second derivatives across the points and across the cycle's end
//! (C. de Boor, *A Practical Guide to Splines*, revised ed., 2001, chapter IV; the periodic
//! end condition). The force at crank angle `theta` (rad, the `crank.angle` input, any number
//! of turns) is `scale F((theta in degrees) mod cycle)`.
//!
//! Inside a communication step the crank angle follows `theta(t) = theta_k + omega_k s +
//! alpha_k s^2 / 2 + j_k s^3 / 6` ([`super::crank`]), so the force follows the crank through every internal
//! step: a coarse communication grid sees the same pulse as a fine one. It acts in addition to
//! the `slider.force` input.

use serde::{Deserialize, Serialize};

use crate::error::ModelError;

/// Most points of a table (one per 0.05 degree of a four-stroke cycle).
pub const MAX_POINTS: usize = 14_400;

/// Largest |force| of a point and of `scale` times it, N (the `slider.force` input's window).
pub const MAX_FORCE: f64 = 1e8;

/// The scale's window: `[0, MAX_SCALE]`.
pub const MAX_SCALE: f64 = 100.0;

/// The scene table `[slider.gas_force]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GasForceTable {
    /// Crank angle of one cycle, degrees, in (0, 3600].
    pub cycle: f64,
    /// Crank angles of the points, degrees, strictly ascending within [0, cycle).
    pub angle: Vec<f64>,
    /// Force on the slider along +x at each point, N.
    pub force: Vec<f64>,
    /// Factor on the table's force (FMU parameter `slider.gas_force_scale`), in [0, 100].
    #[serde(default = "unit_scale")]
    pub scale: f64,
}

fn unit_scale() -> f64 {
    1.0
}

fn invalid(name: &'static str, value: f64, allowed: String) -> ModelError {
    ModelError::InvalidParameter {
        name,
        value,
        allowed,
    }
}

impl GasForceTable {
    /// Check every number against its documented window (module and field documentation).
    pub fn validate(&self) -> Result<(), ModelError> {
        if !(self.cycle.is_finite() && self.cycle > 0.0 && self.cycle <= 3600.0) {
            return Err(invalid(
                "slider.gas_force.cycle",
                self.cycle,
                "a crank angle in (0, 3600] degrees".into(),
            ));
        }
        let n = self.angle.len();
        if !(3..=MAX_POINTS).contains(&n) || self.force.len() != n {
            return Err(invalid(
                "slider.gas_force.angle",
                n as f64,
                format!(
                    "3 to {MAX_POINTS} points, as many angles as forces ({} forces)",
                    self.force.len()
                ),
            ));
        }
        for (i, &a) in self.angle.iter().enumerate() {
            let above = if i == 0 { 0.0 } else { self.angle[i - 1] };
            let ascending = i == 0 || a > above;
            if !(a.is_finite() && a >= 0.0 && a < self.cycle && ascending) {
                return Err(invalid(
                    "slider.gas_force.angle",
                    a,
                    format!(
                        "strictly ascending crank angles in [0, cycle = {}) degrees",
                        self.cycle
                    ),
                ));
            }
        }
        let mut largest: f64 = 0.0;
        for &f in &self.force {
            if !(f.is_finite() && f.abs() <= MAX_FORCE) {
                return Err(invalid(
                    "slider.gas_force.force",
                    f,
                    format!("a finite force with |force| <= {MAX_FORCE:e} N"),
                ));
            }
            largest = largest.max(f.abs());
        }
        if !(self.scale.is_finite() && (0.0..=MAX_SCALE).contains(&self.scale)) {
            return Err(invalid(
                "slider.gas_force_scale",
                self.scale,
                format!("a factor in [0, {MAX_SCALE}]"),
            ));
        }
        if self.scale * largest > MAX_FORCE {
            return Err(invalid(
                "slider.gas_force_scale",
                self.scale,
                format!(
                    "at most {:e}: the scaled table's largest force must stay within {MAX_FORCE:e} N",
                    MAX_FORCE / largest
                ),
            ));
        }
        Ok(())
    }
}

/// The preprocessed table: the periodic cubic spline, one cubic in powers of the angle from
/// its start per interval, and a bucketed lookup of the intervals.
#[derive(Clone, Debug, PartialEq)]
pub struct GasForce {
    /// Cycle, degrees, and its reciprocal.
    cycle: f64,
    inv_cycle: f64,
    /// The points' angles (degrees) with the first repeated one cycle on, `n + 1`.
    angle: Vec<f64>,
    /// Interval `i`'s cubic `f_i + c_1 d + c_2 d^2 + c_3 d^3`, `d = x - angle_i` (degrees):
    /// `[f_i, c_1, c_2, c_3]` (N, N/deg, N/deg^2, N/deg^3), `n`.
    cubic: Vec<[f64; 4]>,
    /// The lookup: the cycle cut into `n` equal buckets of `1 / inv_bucket` degrees;
    /// `first[k]` is the interval holding the bucket's start, so the interval of an angle in
    /// bucket `k` lies in `first[k] ..= first[k + 1]` (one interval for an evenly spaced table).
    inv_bucket: f64,
    first: Vec<usize>,
}

impl GasForce {
    /// The spline of a validated table.
    pub fn new(table: &GasForceTable) -> Result<GasForce, ModelError> {
        table.validate()?;
        let n = table.angle.len();
        let mut angle = table.angle.clone();
        angle.push(table.angle[0] + table.cycle);
        let mut force: Vec<f64> = table.force.iter().map(|f| table.scale * f).collect();
        force.push(force[0]);
        let h: Vec<f64> = (0..n).map(|i| angle[i + 1] - angle[i]).collect();
        // Periodic spline (de Boor, chapter IV): for every point i (indices mod n)
        // h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1}
        //   = 6 ((f_{i+1} - f_i) / h_i - (f_i - f_{i-1}) / h_{i-1}).
        let below = |i: usize| h[(i + n - 1) % n];
        let diag: Vec<f64> = (0..n).map(|i| 2.0 * (below(i) + h[i])).collect();
        let rhs: Vec<f64> = (0..n)
            .map(|i| {
                let prev = force[(i + n - 1) % n];
                6.0 * ((force[i + 1] - force[i]) / h[i] - (force[i] - prev) / below(i))
            })
            .collect();
        // Sub-diagonal a_i = h_{i-1} (row i, column i-1), super-diagonal c_i = h_i (row i,
        // column i+1), the corners a_0 (row 0, column n-1) and c_{n-1} (row n-1, column 0).
        let sub: Vec<f64> = (0..n).map(below).collect();
        let sup: Vec<f64> = h.clone();
        let mut curvature = cyclic_tridiagonal(&sub, &diag, &sup, &rhs);
        curvature.push(curvature[0]);
        // The spline on interval i in the second derivatives M (de Boor, chapter IV), in powers
        // of d = x - angle_i: f_i + ((f_i+1 - f_i) / h - h (2 M_i + M_i+1) / 6) d + M_i / 2 d^2
        // + (M_i+1 - M_i) / (6 h) d^3.
        let cubic = (0..n)
            .map(|i| {
                let (m0, m1) = (curvature[i], curvature[i + 1]);
                [
                    force[i],
                    (force[i + 1] - force[i]) / h[i] - h[i] * (2.0 * m0 + m1) / 6.0,
                    0.5 * m0,
                    (m1 - m0) / (6.0 * h[i]),
                ]
            })
            .collect();
        let bucket = table.cycle / n as f64;
        let first = (0..=n)
            .map(|k| interval(&angle, angle[0] + k as f64 * bucket, 0, n - 1))
            .collect();
        Ok(GasForce {
            cycle: table.cycle,
            inv_cycle: 1.0 / table.cycle,
            angle,
            cubic,
            inv_bucket: 1.0 / bucket,
            first,
        })
    }

    /// The force at crank angle `theta` (rad), N.
    pub fn at(&self, theta: f64) -> f64 {
        let x = self.within_cycle(theta);
        let i = self.interval_of(x);
        let [f, c1, c2, c3] = self.cubic[i];
        let d = x - self.angle[i];
        f + d * (c1 + d * (c2 + d * c3))
    }

    /// The crank angle `theta` (rad) in degrees within the cycle from the first point,
    /// `[angle_0, angle_0 + cycle]` (the whole turns taken off by truncation, not a remainder:
    /// the same interval up to round-off at the cycle's end, where the spline is continuous).
    fn within_cycle(&self, theta: f64) -> f64 {
        let start = self.angle[0];
        let from_start = theta.to_degrees() - start;
        let turns = from_start * self.inv_cycle;
        let mut whole = turns as i64 as f64;
        if whole > turns {
            whole -= 1.0;
        }
        (from_start - whole * self.cycle).clamp(0.0, self.cycle) + start
    }

    /// The interval `[angle_i, angle_i+1]` holding `x` (degrees within the cycle), searched
    /// in `x`'s bucket only.
    fn interval_of(&self, x: f64) -> usize {
        let last = self.angle.len() - 2;
        let k = (((x - self.angle[0]) * self.inv_bucket) as usize).min(self.first.len() - 2);
        let mut lo = self.first[k];
        if lo > 0 && self.angle[lo] > x {
            // x just below its bucket's start by round-off in the product.
            lo -= 1;
        }
        interval(&self.angle, x, lo, self.first[k + 1].min(last))
    }
}

/// The index `i` in `lo ..= hi` of the interval `[angle_i, angle_i+1]` holding `x`: the last
/// `i` with `angle_i <= x` (`lo` if none).
fn interval(angle: &[f64], x: f64, lo: usize, hi: usize) -> usize {
    lo + angle[lo + 1..=hi].partition_point(|&a| a <= x)
}

/// Solve the cyclic tridiagonal system with sub-diagonal `a` (`a[0]` in the top-right corner),
/// diagonal `b`, super-diagonal `c` (`c[n-1]` in the bottom-left corner) and right side `r`,
/// by the Sherman-Morrison correction of the Thomas algorithm (W. H. Press et al., *Numerical
/// Recipes*, 3rd ed., 2007, section 2.7.2). The spline's matrix is strictly diagonally
/// dominant, so no pivoting is needed.
fn cyclic_tridiagonal(a: &[f64], b: &[f64], c: &[f64], r: &[f64]) -> Vec<f64> {
    let n = b.len();
    let (alpha, beta) = (c[n - 1], a[0]);
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] = b[0] - gamma;
    bb[n - 1] = b[n - 1] - alpha * beta / gamma;
    let x = tridiagonal(a, &bb, c, r);
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = alpha;
    let z = tridiagonal(a, &bb, c, &u);
    let fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
    x.iter().zip(&z).map(|(xi, zi)| xi - fact * zi).collect()
}

/// Thomas algorithm for the tridiagonal system (`a[0]` and `c[n-1]` unused).
fn tridiagonal(a: &[f64], b: &[f64], c: &[f64], r: &[f64]) -> Vec<f64> {
    let n = b.len();
    let mut cp = vec![0.0; n];
    let mut x = vec![0.0; n];
    let mut den = b[0];
    x[0] = r[0] / den;
    for i in 1..n {
        cp[i - 1] = c[i - 1] / den;
        den = b[i] - a[i] * cp[i - 1];
        x[i] = (r[i] - a[i] * x[i - 1]) / den;
    }
    for i in (0..n - 1).rev() {
        x[i] -= cp[i] * x[i + 1];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(cycle: f64, n: usize, f: impl Fn(f64) -> f64) -> GasForceTable {
        let angle: Vec<f64> = (0..n).map(|i| cycle * i as f64 / n as f64).collect();
        GasForceTable {
            cycle,
            force: angle.iter().map(|&a| f(a)).collect(),
            angle,
            scale: 1.0,
        }
    }

    #[test]
    fn spline_passes_through_its_points_and_repeats_every_cycle() {
        let t = GasForceTable {
            cycle: 720.0,
            angle: vec![0.0, 10.0, 35.0, 300.0, 700.0],
            force: vec![-1e3, -4e4, -2e4, 0.0, 5e2],
            scale: 2.0,
        };
        let g = GasForce::new(&t).unwrap();
        for (a, f) in t.angle.iter().zip(&t.force) {
            for turns in [-3.0, 0.0, 1.0, 7.0] {
                let theta = (a + turns * 720.0).to_radians();
                assert!((g.at(theta) - 2.0 * f).abs() < 1e-9 * 8e4, "{a} {turns}");
            }
        }
    }

    /// The bucketed lookup gives the force of a search over the whole table, on an even table,
    /// an uneven one and one with most of its points clustered in one degree, at angles across
    /// many turns both ways, at the points and at the buckets' edges.
    #[test]
    fn bucketed_lookup_matches_a_search_of_the_whole_table() {
        let even = table(1440.0, 2880, |a| {
            -3.8e4 * (-((a - 735.0) / 20.0).powi(2)).exp()
        });
        let mut clustered: Vec<f64> = (0..400).map(|i| 100.0 + i as f64 * 0.0025).collect();
        clustered.extend([0.0, 50.0, 300.0, 500.0, 719.5]);
        clustered.sort_by(f64::total_cmp);
        let uneven = |angle: Vec<f64>, cycle: f64| GasForceTable {
            cycle,
            force: angle.iter().map(|a| (a * 0.1).sin() * 1e4 + a).collect(),
            angle,
            scale: 1.5,
        };
        for t in [
            even,
            uneven(
                vec![30.0, 31.0, 45.0, 90.0, 91.5, 200.0, 333.0, 359.0],
                360.0,
            ),
            uneven(clustered, 720.0),
        ] {
            let g = GasForce::new(&t).unwrap();
            // The interval by a search of the whole table, the angle as a remainder.
            let searched = |theta: f64| {
                let first = g.angle[0];
                let x = (theta.to_degrees() - first).rem_euclid(g.cycle) + first;
                let i = g
                    .angle
                    .partition_point(|&a| a <= x)
                    .clamp(1, g.angle.len() - 1)
                    - 1;
                let [f, c1, c2, c3] = g.cubic[i];
                let d = x - g.angle[i];
                f + d * (c1 + d * (c2 + d * c3))
            };
            let scale = g.cubic.iter().fold(0.0f64, |m, c| m.max(c[0].abs()));
            let mut angles: Vec<f64> = (0..20_000).map(|k| -5000.0 + k as f64 * 0.6173).collect();
            angles.extend(
                t.angle
                    .iter()
                    .flat_map(|a| [*a, a + t.cycle, a - 3.0 * t.cycle]),
            );
            angles.extend((0..=40).map(|k| t.angle[0] + k as f64 * t.cycle / t.angle.len() as f64));
            for deg in angles {
                let theta = deg.to_radians();
                let (got, want) = (g.at(theta), searched(theta));
                assert!(
                    (got - want).abs() <= 1e-9 * scale,
                    "{deg} deg: {got} vs {want}"
                );
            }
        }
    }

    /// The cyclic tridiagonal solve against a dense solve of the same periodic system, on an
    /// uneven table that starts at 30 degrees, with three points and with nine; and the spline's
    /// slope and curvature from both sides of the cycle's end (between the last point and the
    /// first one cycle on) agree.
    #[test]
    fn periodic_spline_matches_a_dense_solve_on_uneven_tables() {
        for angle in [
            vec![30.0, 100.0, 250.0],
            vec![30.0, 31.0, 45.0, 90.0, 91.5, 200.0, 333.0, 350.0, 359.0],
        ] {
            let t = GasForceTable {
                cycle: 360.0,
                force: angle
                    .iter()
                    .map(|a: &f64| 1e3 * (a.to_radians() * 2.0).cos() + 0.5 * a)
                    .collect(),
                angle: angle.clone(),
                scale: 1.0,
            };
            let g = GasForce::new(&t).unwrap();
            let n = angle.len();
            let h: Vec<f64> = (0..n).map(|i| g.angle[i + 1] - g.angle[i]).collect();
            let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
            let mut r = nalgebra::DVector::<f64>::zeros(n);
            for i in 0..n {
                let (prev, next) = ((i + n - 1) % n, (i + 1) % n);
                let hp = h[prev];
                a[(i, prev)] += hp;
                a[(i, i)] += 2.0 * (hp + h[i]);
                a[(i, next)] += h[i];
                let force = |i: usize| g.cubic[i % n][0];
                r[i] = 6.0 * ((force(i + 1) - force(i)) / h[i] - (force(i) - force(prev)) / hp);
            }
            let dense = a.lu().solve(&r).unwrap();
            for i in 0..n {
                assert!(
                    // The cubic's d^2 coefficient is half the second derivative at its start.
                    (2.0 * g.cubic[i][2] - dense[i]).abs() < 1e-9 * dense.amax(),
                    "{angle:?}: {i}"
                );
            }
            // One-sided differences at the first point, from below (the end of the cycle) and
            // from above.
            let d = 1e-4f64;
            let x0 = angle[0];
            let f = |x: f64| g.at(x.to_radians());
            let slope = |s: f64| (f(x0 + s * d) - f(x0 + s * 2.0 * d)) / (-s * d);
            let (below, above) = (slope(-1.0), slope(1.0));
            assert!(
                (below - above).abs() < 1e-3 * below.abs().max(1.0),
                "{below} {above}"
            );
            let curv = |s: f64| {
                (f(x0 + s * 3.0 * d) - 2.0 * f(x0 + s * 2.0 * d) + f(x0 + s * d)) / (d * d)
            };
            let (below, above) = (curv(-1.0), curv(1.0));
            assert!(
                (below - above).abs() < 1e-2 * below.abs().max(1.0),
                "{below} {above}"
            );
        }
    }

    #[test]
    fn spline_is_smooth_across_the_cycle_end() {
        // Second differences on both sides of the wrap agree: C2 at the cycle's end.
        let g = GasForce::new(&table(360.0, 7, |a| (a.to_radians()).sin() * 1e3)).unwrap();
        let d = 1e-3f64;
        let curv = |x: f64| {
            (g.at((x + d).to_radians()) - 2.0 * g.at(x.to_radians()) + g.at((x - d).to_radians()))
                / (d * d)
        };
        let (left, right) = (curv(360.0 - 10.0 * d), curv(360.0 + 10.0 * d));
        assert!(
            (left - right).abs() < 1e-3 * left.abs().max(1.0),
            "{left} {right}"
        );
    }

    #[test]
    fn spline_converges_to_a_smooth_pulse_at_fourth_order() {
        // The pulse -38 kN exp(-((a - 375) / 20)^2) over a four-stroke cycle: the largest
        // error over the cycle falls 16 times per halved spacing (de Boor, chapter IV: O(h^4)).
        let pulse = |a: f64| -38e3 * (-((a - 375.0) / 20.0).powi(2)).exp();
        let err = |n: usize| {
            let g = GasForce::new(&table(720.0, n, pulse)).unwrap();
            (0..7200)
                .map(|k| {
                    let a = k as f64 * 0.1;
                    (g.at(a.to_radians()) - pulse(a)).abs()
                })
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (err(360), err(720));
        let order = (coarse / fine).log2();
        assert!(
            (3.6..4.4).contains(&order),
            "order {order}: {coarse} {fine}"
        );
        assert!(fine < 38e3 * 1e-4, "{fine}");
    }

    #[test]
    fn bad_tables_are_refused_with_the_value_and_its_window() {
        let good = table(720.0, 8, |a| -a);
        assert!(good.validate().is_ok());
        type Spoil = Box<dyn Fn(&mut GasForceTable)>;
        let cases: [(&str, Spoil); 7] = [
            ("slider.gas_force.cycle", Box::new(|t| t.cycle = 0.0)),
            ("slider.gas_force.angle", Box::new(|t| t.angle.truncate(2))),
            (
                "slider.gas_force.angle",
                Box::new(|t| t.angle[3] = t.angle[2]),
            ),
            ("slider.gas_force.angle", Box::new(|t| t.angle[7] = 720.0)),
            (
                "slider.gas_force.force",
                Box::new(|t| t.force[1] = f64::NAN),
            ),
            ("slider.gas_force_scale", Box::new(|t| t.scale = -1.0)),
            (
                "slider.gas_force_scale",
                Box::new(|t| {
                    t.force[1] = 9e7;
                    t.scale = 2.0;
                }),
            ),
        ];
        for (name, spoil) in cases {
            let mut t = good.clone();
            spoil(&mut t);
            match t.validate() {
                Err(ModelError::InvalidParameter {
                    name: got, allowed, ..
                }) => {
                    assert_eq!(got, name);
                    assert!(!allowed.is_empty());
                }
                other => panic!("{name}: {other:?}"),
            }
        }
    }
}
