//! Everything the beam layer needs to know about a rod: material, length, the section along
//! it, whether shear deforms it, and the rigid bodies at its ends.

use super::section::RodProperties;
use super::section_table::{End, EndBody, SectionTable};
use crate::error::ModelError;

/// A straight rod B-C. SI units.
#[derive(Clone, Debug, PartialEq)]
pub struct RodDefinition {
    /// Length, E, rho; `area` and `area_moment` are the section's if `table` is `None`, else
    /// the table's length means (for messages and equivalent-uniform estimates only).
    pub properties: RodProperties,
    /// The section along the rod; `None` = the uniform section of `properties`, computed with
    /// the closed-form Euler-Bernoulli element matrices (the original path, unchanged).
    pub table: Option<SectionTable>,
    /// Shear modulus G, Pa, when the rod is shear-deformable (Timoshenko); `None` =
    /// Euler-Bernoulli.
    pub shear_modulus: Option<f64>,
    /// Shear area of the uniform rod, m^2 (`None`: `A / 1.2`); a table gives it per station.
    pub uniform_shear_area: Option<f64>,
    /// Rigid body at B (big end) and at C (small end).
    pub big_end: EndBody,
    pub small_end: EndBody,
}

/// The shear modulus window: finite and at least the lower end of Young's modulus window
/// (`PHYSICAL_RANGES`) a decade lower, `G = E / (2 (1 + nu))`; no upper end: a rigid-shear limit
/// is the Rayleigh beam.
pub fn check_shear_modulus(g: f64) -> Result<(), ModelError> {
    let low = super::section::PHYSICAL_RANGES[1].0 / 10.0;
    if g.is_finite() && g >= low {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name: "rod.shear_modulus",
            value: g,
            allowed: format!("a finite value >= {low:e} Pa"),
        })
    }
}

impl RodDefinition {
    /// The uniform Euler-Bernoulli rod without end bodies.
    pub fn uniform(properties: RodProperties) -> RodDefinition {
        RodDefinition {
            properties,
            table: None,
            shear_modulus: None,
            uniform_shear_area: None,
            big_end: EndBody::default(),
            small_end: EndBody::default(),
        }
    }

    /// A rod with a station table (already validated for `properties.length`); `properties`'
    /// area and area moment are replaced by the table's means.
    pub fn with_table(properties: RodProperties, table: SectionTable) -> RodDefinition {
        let l = properties.length;
        let (a, i) = table
            .integrate(0.0, l, super::section_element::Pair(0.0, 0.0), |_, v, w| {
                super::section_element::Pair(v.area * w, v.area_moment * w)
            })
            .into_tuple();
        RodDefinition {
            properties: RodProperties {
                area: a / l,
                area_moment: i / l,
                ..properties
            },
            table: Some(table),
            shear_modulus: None,
            uniform_shear_area: None,
            big_end: EndBody::default(),
            small_end: EndBody::default(),
        }
    }

    /// Whether this is the uniform Euler-Bernoulli rod without end bodies, computed with the
    /// closed-form element matrices.
    pub fn is_plain(&self) -> bool {
        self.table.is_none()
            && self.shear_modulus.is_none()
            && self.uniform_shear_area.is_none()
            && self.big_end.is_empty()
            && self.small_end.is_empty()
    }

    /// The section table (a one-station table for the uniform rod).
    pub fn section_table(&self) -> SectionTable {
        match &self.table {
            Some(t) => t.clone(),
            None => SectionTable::uniform(
                self.properties.length,
                self.properties.area,
                self.properties.area_moment,
            )
            .with_uniform_shear_area(self.uniform_shear_area),
        }
    }

    /// Every value finite and in range; the error names the first that is not.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.properties.validate()?;
        if let Some(g) = self.shear_modulus {
            check_shear_modulus(g)?;
        }
        if let Some(t) = &self.table {
            t.validate_physical()?;
            if (t.length() - self.properties.length).abs() > 1e-9 * self.properties.length {
                return Err(ModelError::InvalidParameter {
                    name: "rod.length",
                    value: self.properties.length,
                    allowed: format!("the length of the section table, {} m", t.length()),
                });
            }
        }
        self.big_end.validate(End::B)?;
        self.small_end.validate(End::C)
    }

    /// Mass of the rod itself, `int rho A ds`, kg.
    pub fn rod_mass(&self) -> f64 {
        match &self.table {
            None => self.properties.mass(),
            Some(t) => self.properties.density * t.tail_integrals(0.0).0,
        }
    }

    /// Mass of the rod with its end bodies, kg.
    pub fn total_mass(&self) -> f64 {
        self.rod_mass() + self.big_end.mass + self.small_end.mass
    }

    /// Arc length of the centre of mass of rod and end bodies from B, m.
    pub fn centre_of_mass(&self) -> f64 {
        let l = self.properties.length;
        let first = match &self.table {
            None => self.properties.mass() * 0.5 * l,
            Some(t) => self.properties.density * t.tail_integrals(0.0).1,
        };
        (first + self.small_end.mass * l) / self.total_mass()
    }
}
