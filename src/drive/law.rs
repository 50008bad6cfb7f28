//! Crank motions for driving the model: the input `(theta_k, omega_k, alpha_k)` at each
//! communication point `t_k`, the motion's own values there, with no jerk (the FMU's input
//! law then holds between the points: `theta(t_k + s) = theta_k + omega_k s + alpha_k s^2 / 2`;
//! a master that continues the law with a jerk: `flexrod::drive::engine`).

use crate::error::ModelError;
use crate::mechanism::CrankInput;

/// A prescribed crank motion, angles in rad, speeds in rad/s, times in s from `t = 0`.
#[derive(Clone, Debug, PartialEq)]
pub enum CrankDrive {
    /// `theta = w t`, `omega = w`.
    Constant { speed: f64 },
    /// `theta = w0 t + a t^2 / 2`, `omega = w0 + a t`, `alpha = a`.
    UniformAcceleration { speed: f64, acceleration: f64 },
    /// Smooth start from rest to `speed` over `time` T:
    /// `omega = W (1 - cos(pi t / T)) / 2`, `theta = W/2 (t - T/pi sin(pi t / T))`,
    /// `alpha = W pi / (2 T) sin(pi t / T)` for `t < T`; then constant speed W.
    Ramp { speed: f64, time: f64 },
    /// Rows `[t, theta, omega]`, ascending in t: linear between rows, with `alpha` the slope
    /// of omega; outside the table the crank turns at the nearest end row's speed
    /// (`theta = theta_end + omega_end (t - t_end)`, `alpha = 0`).
    Table(Vec<[f64; 3]>),
}

impl CrankDrive {
    /// The crank input at time `t`.
    pub fn at(&self, t: f64) -> CrankInput {
        match self {
            CrankDrive::Constant { speed } => CrankInput {
                angle: speed * t,
                speed: *speed,
                acceleration: 0.0,
                jerk: 0.0,
            },
            CrankDrive::UniformAcceleration {
                speed,
                acceleration,
            } => CrankInput {
                angle: speed * t + 0.5 * acceleration * t * t,
                speed: speed + acceleration * t,
                acceleration: *acceleration,
                jerk: 0.0,
            },
            CrankDrive::Ramp { speed, time } => {
                let (w, tr) = (*speed, *time);
                if t < tr {
                    let x = std::f64::consts::PI * t / tr;
                    CrankInput {
                        angle: 0.5 * w * (t - tr / std::f64::consts::PI * x.sin()),
                        speed: 0.5 * w * (1.0 - x.cos()),
                        acceleration: 0.5 * w * std::f64::consts::PI / tr * x.sin(),
                        jerk: 0.0,
                    }
                } else {
                    CrankInput {
                        angle: 0.5 * w * tr + w * (t - tr),
                        speed: w,
                        acceleration: 0.0,
                        jerk: 0.0,
                    }
                }
            }
            CrankDrive::Table(rows) => {
                // Outside the table the crank turns on at the speed of its nearest end row:
                // angle and speed stay consistent (theta' = omega, omega' = 0).
                let (first, last) = (rows[0], rows[rows.len() - 1]);
                for end in [first, last] {
                    if (end == first && t < first[0]) || (end == last && t > last[0]) {
                        return CrankInput {
                            angle: end[1] + end[2] * (t - end[0]),
                            speed: end[2],
                            acceleration: 0.0,
                            jerk: 0.0,
                        };
                    }
                }
                let i = rows.partition_point(|r| r[0] <= t).clamp(1, rows.len() - 1);
                let (a, b) = (rows[i - 1], rows[i]);
                let u = ((t - a[0]) / (b[0] - a[0])).clamp(0.0, 1.0);
                CrankInput {
                    angle: a[1] + u * (b[1] - a[1]),
                    speed: a[2] + u * (b[2] - a[2]),
                    acceleration: (b[2] - a[2]) / (b[0] - a[0]),
                    jerk: 0.0,
                }
            }
        }
    }

    /// A table from CSV text: rows `t, angle, speed` (a header line and comment lines that do
    /// not start with a number are skipped); at least two rows, at most
    /// [`crate::limits::MAX_POINTS`], times strictly increasing. A line a message quotes is cut
    /// to [`crate::text::ECHO_CHARS`] characters.
    pub fn table_from_csv(text: &str, origin: &str) -> Result<CrankDrive, ModelError> {
        let bad = |message: String| ModelError::Scene {
            origin: origin.to_string(),
            message,
        };
        let mut rows: Vec<[f64; 3]> = Vec::new();
        for (k, line) in text.lines().enumerate() {
            let starts_numeric = line
                .trim_start()
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '+' || c == '.');
            if !starts_numeric {
                continue;
            }
            let values: Vec<f64> = line
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| {
                    bad(format!(
                        "line {}: not a number in '{}'",
                        k + 1,
                        crate::text::echo(line)
                    ))
                })?;
            if values.len() < 3 || values.iter().any(|x| !x.is_finite()) {
                return Err(bad(format!(
                    "line {}: a row needs three finite numbers t, angle, speed: '{}'",
                    k + 1,
                    crate::text::echo(line)
                )));
            }
            if let Some(last) = rows.last() {
                if values[0] <= last[0] {
                    return Err(bad(format!(
                        "line {}: time {} does not increase (previous {})",
                        k + 1,
                        crate::text::time(values[0]),
                        crate::text::time(last[0])
                    )));
                }
            }
            if rows.len() == crate::limits::MAX_POINTS {
                return Err(bad(format!(
                    "line {}: more than {} rows, the most a table holds (as many as the communication points a run records)",
                    k + 1,
                    crate::limits::MAX_POINTS
                )));
            }
            rows.push([values[0], values[1], values[2]]);
        }
        if rows.len() < 2 {
            return Err(bad("needs at least two rows of t, angle, speed".to_string()));
        }
        Ok(CrankDrive::Table(rows))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Angle, speed and acceleration of every law are consistent derivatives.
    #[test]
    fn laws_are_consistent() {
        let laws = [
            CrankDrive::Constant { speed: 150.0 },
            CrankDrive::UniformAcceleration {
                speed: 50.0,
                acceleration: 2000.0,
            },
            CrankDrive::Ramp {
                speed: 150.0,
                time: 0.02,
            },
        ];
        let d = 1e-6;
        for law in &laws {
            for t in [0.003, 0.011, 0.019, 0.03] {
                let (a, b, c) = (law.at(t - d), law.at(t), law.at(t + d));
                let speed = (c.angle - a.angle) / (2.0 * d);
                let acceleration = (c.speed - a.speed) / (2.0 * d);
                assert!(
                    (speed - b.speed).abs() < 1e-6 * (1.0 + b.speed.abs()),
                    "{law:?} t {t}"
                );
                assert!(
                    (acceleration - b.acceleration).abs() < 1e-4 * (1.0 + b.acceleration.abs()),
                    "{law:?} t {t}"
                );
            }
        }
        // A table continues past its ends at the end rows' speeds, consistently.
        let table = CrankDrive::Table(vec![[0.0, 0.0, 100.0], [0.01, 1.5, 200.0]]);
        for (t, angle, speed) in [(-0.01, -1.0, 100.0), (0.02, 3.5, 200.0)] {
            let input = table.at(t);
            assert!(
                (input.angle - angle).abs() < 1e-12,
                "table at {t}: {input:?}"
            );
            assert_eq!(
                (input.speed, input.acceleration),
                (speed, 0.0),
                "table at {t}"
            );
        }
        let ramp = laws[2].at(0.02);
        assert!((ramp.speed - 150.0).abs() < 1e-12 && ramp.acceleration.abs() < 1e-9);
    }

    #[test]
    fn table_interpolates_and_rejects_bad_rows() {
        let t = CrankDrive::table_from_csv("t,angle,speed\n0,0,0\n1,50,100\n", "x.csv").unwrap();
        let i = t.at(0.5);
        assert_eq!((i.angle, i.speed, i.acceleration), (25.0, 50.0, 100.0));
        let e = CrankDrive::table_from_csv("0,0,0\n0,1,1\n", "x.csv").unwrap_err();
        assert!(e.to_string().contains("does not increase"), "{e}");
        let e = CrankDrive::table_from_csv("0,0\n1,1\n", "x.csv").unwrap_err();
        assert!(e.to_string().contains("three finite numbers"), "{e}");
    }
}
