//! The benchmark cases: how the crank is driven, and the slider.

use flexrod::drive::CrankDrive;
use flexrod::scene::DeflectionPolicy;

/// A benchmark case.
#[derive(Clone, Debug)]
pub struct Case {
    pub key: &'static str,
    pub title: &'static str,
    /// The crank law ([`CrankDrive::Constant`] from t = 0, or [`CrankDrive::Ramp`] from rest).
    pub drive: CrankDrive,
    pub slider_mass: f64,
    /// What a step past `rod.deflection_limit` does in this case.
    pub deflection_policy: DeflectionPolicy,
}

impl Case {
    /// Final crank speed, rad/s.
    pub fn speed(&self) -> f64 {
        match self.drive {
            CrankDrive::Constant { speed } | CrankDrive::Ramp { speed, .. } => speed,
            _ => unreachable!("the report's cases are constant speed or a ramp"),
        }
    }

    /// Length of the start ramp, s (0 for a constant speed from t = 0).
    fn ramp_time(&self) -> f64 {
        match self.drive {
            CrankDrive::Ramp { time, .. } => time,
            _ => 0.0,
        }
    }

    /// Two revolutions of the final speed after the start (after the ramp, if any).
    pub fn duration(&self) -> f64 {
        self.ramp_time() + 4.0 * std::f64::consts::PI / self.speed()
    }

    /// Abrupt start: the axial modes ring, so forces are compared after the low-pass.
    pub fn abrupt(&self) -> bool {
        matches!(self.drive, CrankDrive::Constant { .. })
    }
}

pub fn cases() -> Vec<Case> {
    vec![
        Case {
            key: "a",
            title: "(a) constant 150 rad/s from t = 0, undeformed",
            drive: CrankDrive::Constant { speed: 150.0 },
            slider_mass: 0.0,
            deflection_policy: DeflectionPolicy::Discard,
        },
        Case {
            key: "b",
            title: "(b) smooth start from rest to 150 rad/s in T = 0.02 s",
            drive: CrankDrive::Ramp {
                speed: 150.0,
                time: 0.02,
            },
            slider_mass: 0.0,
            deflection_policy: DeflectionPolicy::Discard,
        },
        Case {
            key: "c",
            title: "(c) constant 300 rad/s (rod.deflection_policy warn: the FFR rod passes the 0.05 L limit)",
            drive: CrankDrive::Constant { speed: 300.0 },
            slider_mass: 0.0,
            deflection_policy: DeflectionPolicy::Warn,
        },
        Case {
            key: "d",
            title: "(d) 150 rad/s, slider mass 0.03 kg",
            drive: CrankDrive::Constant { speed: 150.0 },
            slider_mass: 0.03,
            deflection_policy: DeflectionPolicy::Discard,
        },
    ]
}
