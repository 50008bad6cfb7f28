//! What a scene says about the rod: which model, its section, mesh and modes.

use serde::{Deserialize, Serialize};

use crate::beam::{MassKind, RodProperties};
use crate::modal::ReferenceKind;

/// Which rod model computes the connecting rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RodModelKind {
    /// Floating frame of reference with component modes (seeds 000 and 001).
    Ffr,
    /// Rigid segments joined by rotational springs (seed 002).
    Segments,
}

impl RodModelKind {
    /// Every variant, in the order of the FMU's enumeration items and Integer codes (1-based).
    pub const ALL: [RodModelKind; 2] = [RodModelKind::Ffr, RodModelKind::Segments];

    /// The name used in scenes, the FMU's enumeration items and messages.
    pub fn name(self) -> &'static str {
        match self {
            RodModelKind::Ffr => "ffr",
            RodModelKind::Segments => "segments",
        }
    }

    /// The variant of a name (see [`Self::name`]).
    pub fn from_name(name: &str) -> Option<RodModelKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The connecting rod B-C.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodSpec {
    pub model: RodModelKind,
    /// Rod length L, m.
    pub length: f64,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Cross-section area A, m^2.
    pub area: f64,
    /// Second moment of area I, m^4.
    pub area_moment: f64,
    /// Modal damping ratio (FFR) or joint damping ratio of the first bending mode (segments); 0 = undamped.
    #[serde(default)]
    pub damping_ratio: f64,
    /// Beam elements (FFR) or rigid segments (segments).
    pub elements: usize,
    /// Reference conditions (FFR only).
    #[serde(default = "default_reference")]
    pub reference: ReferenceKind,
    /// Retained modes (FFR only), lowest first.
    #[serde(default = "default_modes")]
    pub modes: usize,
    /// Consistent or lumped element mass (FFR only).
    #[serde(default)]
    pub mass: MassKind,
    /// Axial force acting on bending (geometric stiffness); docs/physics.md, "What linear modes miss".
    #[serde(default = "default_true")]
    pub axial_stiffening: bool,
    /// Segments only: keep the axial springs E A / l (prismatic joints) between segments.
    #[serde(default)]
    pub axial_springs: bool,
}

impl RodSpec {
    /// The section properties of the uniform rod.
    pub fn properties(&self) -> RodProperties {
        RodProperties {
            length: self.length,
            youngs_modulus: self.youngs_modulus,
            density: self.density,
            area: self.area,
            area_moment: self.area_moment,
        }
    }
}

fn default_reference() -> ReferenceKind {
    ReferenceKind::SimplySupported
}
fn default_modes() -> usize {
    4
}
fn default_true() -> bool {
    true
}
