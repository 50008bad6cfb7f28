//! Material and section properties of a uniform rod.

use crate::error::{require_within, ModelError};

/// Physical windows of the rod properties (SI): length 1 mm to 100 m; Young's modulus from soft
/// rubber (1e5 Pa) to 1e17 Pa (half a million times steel's: the rigid limit is approached
/// numerically); density from foams (10 kg/m^3) to above osmium
/// (1e5); area 1e-10 to 1 m^2; area moment 1e-22 to 1 m^4. Order: L, E, rho, A, I.
pub const PHYSICAL_RANGES: [(f64, f64); 5] = [
    (1e-3, 100.0),
    (1e5, 1e17),
    (10.0, 1e5),
    (1e-10, 1.0),
    (1e-22, 1.0),
];

/// The radius of gyration `sqrt(I / A)` of a section must not exceed the rod length `L`
/// (`I <= A L^2`): beyond that the body is not a rod and beam theory does not hold.
pub fn require_gyration_radius(area: f64, area_moment: f64, length: f64) -> Result<(), ModelError> {
    if area_moment <= area * length * length {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name: "rod.area_moment",
            value: area_moment,
            allowed: format!(
                "at most rod.area * rod.length^2 = {:e} m^4 (the radius of gyration sqrt(I / A) = {:e} m must not exceed the rod length {length} m)",
                area * length * length,
                (area_moment / area).sqrt()
            ),
        })
    }
}

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
    /// The CDI benchmark note (J. O'Shea, "Analysis of the Small-Deformation Connecting Rod"),
    /// table 3: the benchmark connecting rod (each half 0.03781 kg, so rho = 7833.8).
    pub fn cdi_benchmark() -> Self {
        RodProperties {
            length: 0.3048,
            youngs_modulus: 2.068e11,
            density: 7833.8,
            area: 3.167e-5,
            area_moment: 7.981e-11,
        }
    }

    /// Every property must be finite and inside [`PHYSICAL_RANGES`], and the section's
    /// radius of gyration `sqrt(I / A)` at most the length (a rod, not a block); the error
    /// names the first that is not. Together these bound every natural frequency of the rod
    /// below `pi^2 / L sqrt(E / rho)` < 1e12 rad/s (1.6e11 Hz), so no calculated value is beyond the
    /// 1e12 the FMU stands behind.
    pub fn validate(&self) -> Result<(), ModelError> {
        let [l, e, rho, a, i] = PHYSICAL_RANGES;
        require_within("rod.length", self.length, l.0, l.1, "m")?;
        require_within("rod.youngs_modulus", self.youngs_modulus, e.0, e.1, "Pa")?;
        require_within("rod.density", self.density, rho.0, rho.1, "kg/m^3")?;
        require_within("rod.area", self.area, a.0, a.1, "m^2")?;
        require_within("rod.area_moment", self.area_moment, i.0, i.1, "m^4")?;
        require_gyration_radius(self.area, self.area_moment, self.length)
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
