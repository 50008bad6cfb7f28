//! Material and section properties of a uniform rod.

use crate::error::{require_positive, ModelError};

/// A uniform straight rod. SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodProperties {
    /// Length L, m.
    pub length: f64,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Cross-section area A, m^2.
    pub area: f64,
    /// Second moment of area I, m^4.
    pub area_moment: f64,
}

impl RodProperties {
    /// Seed 001, table 3: the benchmark connecting rod (each half 0.03781 kg, so rho = 7833.8).
    pub fn seed001_benchmark() -> Self {
        RodProperties {
            length: 0.3048,
            youngs_modulus: 2.068e11,
            density: 7833.8,
            area: 3.167e-5,
            area_moment: 7.981e-11,
        }
    }

    /// Every property must be finite and > 0; the error names the first that is not.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_positive("rod.length", self.length)?;
        require_positive("rod.youngs_modulus", self.youngs_modulus)?;
        require_positive("rod.density", self.density)?;
        require_positive("rod.area", self.area)?;
        require_positive("rod.area_moment", self.area_moment)
    }

    /// Mass per unit length rho A, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.density * self.area
    }

    /// Total mass rho A L, kg.
    pub fn mass(&self) -> f64 {
        self.mass_per_length() * self.length
    }

    /// Axial stiffness E A, N.
    pub fn axial_rigidity(&self) -> f64 {
        self.youngs_modulus * self.area
    }

    /// Bending stiffness E I, N m^2.
    pub fn bending_rigidity(&self) -> f64 {
        self.youngs_modulus * self.area_moment
    }

    /// Euler buckling load of the pinned-pinned rod, pi^2 E I / L^2, N.
    pub fn euler_buckling_load(&self) -> f64 {
        std::f64::consts::PI.powi(2) * self.bending_rigidity() / self.length.powi(2)
    }
}
