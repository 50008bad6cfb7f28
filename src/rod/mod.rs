//! The connecting rod as a body of the mechanism: the interface the slider-crank needs
//! ([`RodBody`]), and the two models behind it.
//!
//! - [`body`]: the [`RodBody`] trait and the rod's material points;
//! - [`ffr`]: the floating-frame-of-reference rod on component modes (Agrawal and Shabana
//!   1985; the CDI benchmark note of J. O'Shea);
//! - [`segments`]: the finite segment chain (Huston 1991);
//! - [`spec`]: what a scene says about the rod ([`RodSpec`], [`RodModelKind`]);
//! - [`cost`]: what a model costs to build and to evaluate, checked before it is built;
//! - [`build`]: the rod a spec describes.

pub mod body;
pub mod cost;
pub mod ffr;
pub mod physics_choice;
pub mod sections;
pub mod segments;
pub mod spec;

pub use body::{RodBody, RodPoint};
pub use physics_choice::PhysicsChoice;
pub use sections::SectionLoads;
pub use spec::{DeflectionPolicy, PhysicsSwitch, RodModelKind, RodSpec};

use crate::error::ModelError;
use crate::modal::mass_loaded_modes::{axial_coordinate_at_c, AddedMass};
use crate::modal::{ComponentModes, ModeSelection, ReferenceConditions};

/// The FFR rod's choice of modes: which modes it retains (`rod.mode_band_hz`, else the
/// `rod.modes` lowest with `rod.axial_modes`), and the masses added in the eigenproblem
/// (`rod.loaded_modes`: the slider's `slider_mass`, kg, at C's axial coordinate). With a band,
/// the bending modes left out are static corrections ([`ffr::residual`]).
pub fn ffr_mode_choice(spec: &RodSpec, slider_mass: f64) -> (ModeSelection, Vec<AddedMass>) {
    let selection = match spec.mode_band_hz {
        Some(max_hz) => ModeSelection::Cutoff { max_hz },
        None if spec.axial_in_addition => ModeSelection::BendingWithAxial {
            bending: spec.modes,
            axial: spec.min_axial_modes(slider_mass),
        },
        None => ModeSelection::CountWithAxial {
            count: spec.modes,
            axial: spec.min_axial_modes(slider_mass),
        },
    };
    let added = match spec.loaded_modes {
        true => vec![AddedMass {
            coordinate: axial_coordinate_at_c(spec.elements),
            mass: slider_mass,
        }],
        false => Vec::new(),
    };
    (selection, added)
}

/// Build the rod model `spec` asks for: validates the section, preprocesses the modes (FFR)
/// or the chain (segments). `slider_mass` (kg) decides the automatic axial mode
/// ([`RodSpec::min_axial_modes`]).
pub fn build(spec: &RodSpec, slider_mass: f64) -> Result<Box<dyn RodBody>, ModelError> {
    let definition = spec.definition()?;
    match spec.model {
        RodModelKind::Ffr => {
            let reference = ReferenceConditions::from_kind(spec.reference, spec.elements)?;
            let (selection, added) = ffr_mode_choice(spec, slider_mass);
            // Every mode once; the retained ones are selected from them, and the bending modes
            // left out are residual flexibility (static corrections to v_mid,
            // [`ffr::residual`]), with a band or a count of modes alike.
            let all = ComponentModes::from_definition_loaded(
                definition,
                spec.elements,
                reference,
                spec.mass,
                &ModeSelection::Cutoff {
                    max_hz: f64::INFINITY,
                },
                &added,
            )?;
            let modes = all.select(&selection)?;
            check_resolved_frequencies(spec, &modes)?;
            let axial = if spec.axial_stiffening {
                (0..modes.n_modes())
                    .filter(|&j| modes.is_axial(modes.retained[j]))
                    .count()
            } else {
                0
            };
            cost::check_ffr(modes.n_modes(), axial, spec.elements, spec.section.len())?;
            let rod = ffr::FfrRod::new(modes, spec.damping_ratio, spec.axial_stiffening);
            Ok(Box::new(rod.with_residual_flexibility(&all)))
        }
        RodModelKind::Segments => Ok(Box::new(segments::SegmentRod::from_definition(
            &definition,
            spec.elements,
            spec.damping_ratio,
            spec.axial_springs,
        )?)),
        RodModelKind::ModalSegments => {
            let chain = segments::SegmentRod::from_definition(
                &definition,
                spec.elements,
                spec.damping_ratio,
                spec.axial_springs,
            )?;
            let axial = spec.axial_modes.unwrap_or(1);
            let modes = segments::modal::band_modes(&chain, spec.modes);
            Ok(Box::new(segments::ModalSegmentRod::new(
                chain,
                modes,
                axial,
                slider_mass,
            )?))
        }
        RodModelKind::Auto => Err(ModelError::State {
            message: "rod.model = auto is resolved to a rod model before one is built (rod::physics_choice::choose)".into(),
        }),
    }
}

/// The smallest ratio of a retained natural frequency to the highest of the rod's eigenproblem
/// that the eigensolver resolves: its squared frequencies carry an error of about `1e-16`
/// times the largest, so at a ratio of `1e-6` (`1e-12` in the squares) a frequency keeps about
/// four digits. A rod whose bending stiffness is below that (a section far too thin for its
/// length, within each key's own range) has modes of round-off, 0 Hz where the solver clips
/// them, and every step would fail.
pub const MIN_RESOLVED_FREQUENCY_RATIO: f64 = 1e-6;

/// Refuse an FFR rod whose retained natural frequencies are not resolved by its eigenproblem
/// ([`MIN_RESOLVED_FREQUENCY_RATIO`]), naming the section and the frequencies.
fn check_resolved_frequencies(spec: &RodSpec, modes: &ComponentModes) -> Result<(), ModelError> {
    let highest = modes.all_frequencies_hz.iter().copied().fold(0.0, f64::max);
    let lowest = modes
        .retained
        .iter()
        .map(|&k| modes.all_frequencies_hz[k])
        .fold(f64::INFINITY, f64::min);
    if modes.retained.is_empty()
        || (lowest.is_finite() && lowest > MIN_RESOLVED_FREQUENCY_RATIO * highest)
    {
        return Ok(());
    }
    let properties = spec.properties();
    Err(ModelError::InvalidParameter {
        name: "rod.area_moment",
        value: properties.area_moment,
        allowed: format!(
            "a bending stiffness the rod's eigenproblem resolves: its lowest retained natural frequency is {lowest:.3e} Hz, {:.1e} of its highest ({highest:.3e} Hz), below the {MIN_RESOLVED_FREQUENCY_RATIO:e} that keeps four digits (radius of gyration {:.3e} m on a {} m rod: a string, not a beam); a larger rod.area_moment, a shorter rod or fewer rod.elements",
            lowest / highest,
            (properties.area_moment / properties.area).sqrt(),
            properties.length
        ),
    })
}
