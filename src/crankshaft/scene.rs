//! The crankshaft's scene file: its name and description, the `[crankshaft]` table and the
//! `[experiment]`, each value checked against its range (`docs/fmu.md`, "The crankshaft
//! FMU"):
//!
//! | key | unit | range |
//! |---|---|---|
//! | `crankshaft.inertia` J | kg m^2 | [1e-6, 1e6] |
//! | `crankshaft.damping` c | N m s/rad | [0, 1e6] |
//! | `crankshaft.start_angle` | rad | [-1e6, 1e6] |
//! | `crankshaft.start_speed` | rad/s | [-1e4, 1e4] |
//! | `experiment.start_time`, `stop_time` | s | the experiment's range of every scene |
//! | `experiment.step_size` | s | [1e-9, 1], at most the run |

use serde::{Deserialize, Serialize};

use crate::cosimulation::experiment::{check_experiment_times, EXPERIMENT_STEP_RANGE};
use crate::error::{require_within, ModelError};

/// Range of the rotary inertia J, kg m^2.
pub const INERTIA_RANGE: (f64, f64) = (1e-6, 1e6);
/// Range of the loss coefficient c, N m s/rad.
pub const DAMPING_RANGE: (f64, f64) = (0.0, 1e6);
/// Window of the angle, rad (the start angle and every angle a step may reach).
pub const ANGLE_WINDOW: f64 = 1e6;
/// Window of the speed, rad/s (95 000 rpm, the rod's crank speed window).
pub const SPEED_WINDOW: f64 = 1e4;
/// Window of each input torque, N m.
pub const TORQUE_WINDOW: f64 = 1e7;
/// Window of each input torque's rate (its first derivative), N m/s.
pub const TORQUE_RATE_WINDOW: f64 = 1e12;

/// The crankshaft and flywheel.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CrankshaftSpec {
    /// Rotary inertia J of crankshaft and flywheel about the crank axis, kg m^2.
    pub inertia: f64,
    /// Viscous loss coefficient c (bearings, windage), N m s/rad.
    #[serde(default)]
    pub damping: f64,
    /// Angle at the start time, rad.
    #[serde(default)]
    pub start_angle: f64,
    /// Speed at the start time, rad/s.
    #[serde(default)]
    pub start_speed: f64,
}

/// The default experiment.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CrankshaftExperiment {
    #[serde(default)]
    pub start_time: f64,
    pub stop_time: f64,
    pub step_size: f64,
}

/// A crankshaft scene.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CrankshaftScene {
    /// Short identifier; also the FMU's `modelIdentifier`.
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub crankshaft: CrankshaftSpec,
    pub experiment: CrankshaftExperiment,
}

impl CrankshaftScene {
    /// The table that makes a scene file a crankshaft's.
    pub const TABLE: &'static str = "crankshaft";

    /// Parse and check a scene's text; `origin` names it in messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<CrankshaftScene, String> {
        let scene: CrankshaftScene = toml::from_str(text).map_err(|e| {
            format!(
                "scene {origin}: {}",
                crate::text::echo_lines(e.to_string().trim())
            )
        })?;
        scene
            .validate()
            .map_err(|e| format!("scene {origin}: {e}"))?;
        Ok(scene)
    }

    /// The scene as TOML (what [`Self::from_toml_str`] reads back).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// Every value within its range; the error names the key.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.validate_texts()?;
        self.crankshaft.validate()?;
        let e = &self.experiment;
        check_experiment_times(
            e.start_time,
            Some(e.stop_time),
            ["experiment.start_time", "experiment.stop_time"],
        )?;
        let (low, high) = EXPERIMENT_STEP_RANGE;
        require_within(
            "experiment.step_size",
            e.step_size,
            low,
            high.min(e.stop_time - e.start_time),
            "s",
        )
    }

    /// The name is an identifier (it names the binary), the texts carry only characters XML
    /// 1.0 attributes hold.
    fn validate_texts(&self) -> Result<(), ModelError> {
        let identifier = !self.name.is_empty()
            && self.name.len() <= 64
            && self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !self.name.starts_with(|c: char| c.is_ascii_digit());
        if !identifier {
            return Err(ModelError::State {
                message: format!(
                    "name = \"{}\" is not allowed: allowed 1 to 64 ASCII letters, digits and underscores, not starting with a digit (it is the FMU's modelIdentifier)",
                    crate::text::echo(&self.name)
                ),
            });
        }
        if let Some((position, character)) = crate::text::first_non_xml_char(&self.description) {
            return Err(ModelError::InvalidText {
                key: "description",
                character,
                position,
                length: self.description.chars().count(),
            });
        }
        Ok(())
    }
}

impl CrankshaftSpec {
    /// Every parameter within its range; the error names it.
    pub fn validate(&self) -> Result<(), ModelError> {
        let (j, c) = (INERTIA_RANGE, DAMPING_RANGE);
        require_within("crankshaft.inertia", self.inertia, j.0, j.1, "kg m^2")?;
        require_within("crankshaft.damping", self.damping, c.0, c.1, "N m s/rad")?;
        let (a, w) = (ANGLE_WINDOW, SPEED_WINDOW);
        require_within("crankshaft.start_angle", self.start_angle, -a, a, "rad")?;
        require_within("crankshaft.start_speed", self.start_speed, -w, w, "rad/s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "name = \"crankshaft\"\n[crankshaft]\ninertia = 0.25\n[experiment]\nstop_time = 0.1\nstep_size = 1e-3\n";

    #[test]
    fn a_scene_reads_back_from_its_toml() {
        let scene = CrankshaftScene::from_toml_str(SCENE, "test").unwrap();
        assert_eq!(scene.crankshaft.damping, 0.0);
        let again = CrankshaftScene::from_toml_str(&scene.to_toml(), "again").unwrap();
        assert_eq!(again, scene);
    }

    #[test]
    fn values_out_of_range_name_their_key() {
        for (from, to, key) in [
            ("inertia = 0.25", "inertia = 0.0", "crankshaft.inertia"),
            (
                "inertia = 0.25",
                "inertia = 0.25\ndamping = -1",
                "crankshaft.damping",
            ),
            (
                "inertia = 0.25",
                "inertia = 0.25\nstart_speed = 1e9",
                "crankshaft.start_speed",
            ),
            (
                "step_size = 1e-3",
                "step_size = 1.0",
                "experiment.step_size",
            ),
            (
                "inertia = 0.25",
                "inertia = 0.25\nmass = 3",
                "unknown field",
            ),
            (
                "name = \"crankshaft\"",
                "name = \"crank shaft\"",
                "modelIdentifier",
            ),
        ] {
            let e =
                CrankshaftScene::from_toml_str(&SCENE.replace(from, to), "test").expect_err(key);
            assert!(e.contains(key), "{key}: {e}");
        }
    }
}
