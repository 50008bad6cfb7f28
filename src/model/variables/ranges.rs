//! The range checks of the Integer and Enumeration parameters at the set call. An `Err`
//! carries the allowed values for the message; the physical ranges are checked when the model
//! is built (`Simulation::new`).

use super::enumerations::{self, Kind, PHYSICS_SWITCH, ROD_MODEL, ROD_REFERENCE};
use crate::beam::mesh::MAX_ELEMENTS;
use crate::cosimulation::EnumerationType;
use crate::rod::PhysicsSwitch;
use crate::scene::{DeflectionPolicy, ReferenceKind, RodModelKind, Scene};

/// `rod.elements`: the largest value, as the Integer of the `max` attribute.
pub const ELEMENTS_MAX: i32 = MAX_ELEMENTS as i32;

/// A count as an Integer value (saturating).
pub fn usize_to_i32(n: usize) -> i32 {
    i32::try_from(n).unwrap_or(i32::MAX)
}

/// A count `>= 0`.
pub fn non_negative(value: i32) -> Result<usize, String> {
    usize::try_from(value).map_err(|_| "an integer >= 0".to_string())
}

/// `rod.elements`: the core's mesh takes 1..=MAX_ELEMENTS elements.
pub fn element_count(value: i32) -> Result<usize, String> {
    match usize::try_from(value) {
        Ok(n) if (1..=MAX_ELEMENTS).contains(&n) => Ok(n),
        _ => Err(format!(
            "an integer in 1..={MAX_ELEMENTS} (beam elements or rigid segments; both models are limited to {MAX_ELEMENTS})"
        )),
    }
}

/// The variant of an enumeration code, or the allowed items.
fn kind<K: Kind>(ty: &EnumerationType, value: i32) -> Result<K, String> {
    enumerations::from_code(value).ok_or_else(|| ty.allowed_text())
}

/// `rod.model`: 1 (ffr), 2 (segments), 3 (modal_segments), 4 (auto).
pub fn set_model(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.model = kind::<RodModelKind>(&ROD_MODEL, value)?;
    Ok(())
}

/// `rod.shear_deformation`: 1 (auto), 2 (on), 3 (off).
pub fn set_shear_deformation(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.shear_deformation = kind::<PhysicsSwitch>(&PHYSICS_SWITCH, value)?;
    Ok(())
}

/// `rod.axial_dynamics`: 1 (auto), 2 (on), 3 (off).
pub fn set_axial_dynamics(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.axial_dynamics = kind::<PhysicsSwitch>(&PHYSICS_SWITCH, value)?;
    Ok(())
}

/// `rod.reference`: 1 (simply_supported) .. 4 (cantilever).
pub fn set_reference(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.reference = kind::<ReferenceKind>(&ROD_REFERENCE, value)?;
    Ok(())
}

/// `rod.deflection_policy` as an Integer: 1 warn, 2 discard, 3 error (the order of
/// [`DeflectionPolicy::ALL`]).
pub fn policy_code(policy: DeflectionPolicy) -> i32 {
    let position = DeflectionPolicy::ALL.iter().position(|&p| p == policy);
    usize_to_i32(position.unwrap_or(0) + 1)
}

/// `rod.deflection_policy`: 1 (warn), 2 (discard), 3 (error).
pub fn set_policy(scene: &mut Scene, value: i32) -> Result<(), String> {
    let policy = usize::try_from(value)
        .ok()
        .and_then(|code| code.checked_sub(1))
        .and_then(|index| DeflectionPolicy::ALL.get(index));
    match policy {
        Some(&p) => {
            scene.rod.deflection_policy = p;
            Ok(())
        }
        None => Err("1 (warn), 2 (discard) or 3 (error)".to_string()),
    }
}

/// `rod.loaded_modes` as an Integer: 0 free modes, 1 mass-loaded modes.
pub fn loaded_modes_code(scene: &Scene) -> i32 {
    i32::from(scene.rod.loaded_modes)
}

/// `rod.loaded_modes`: 0 (free modes), 1 (mass-loaded modes).
pub fn set_loaded_modes(scene: &mut Scene, value: i32) -> Result<(), String> {
    match value {
        0 | 1 => {
            scene.rod.loaded_modes = value == 1;
            Ok(())
        }
        _ => Err(
            "0 (free modes) or 1 (mass-loaded modes: the slider's mass at C in the eigenproblem)"
                .to_string(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enumeration_setters_check_items() {
        let mut scene = Scene::benchmark();
        assert!(set_model(&mut scene, 2).is_ok());
        assert_eq!(scene.rod.model, RodModelKind::Segments);
        assert!(set_model(&mut scene, 3).is_ok());
        assert_eq!(scene.rod.model, RodModelKind::ModalSegments);
        assert!(set_model(&mut scene, 4).is_ok());
        assert_eq!(scene.rod.model, RodModelKind::Auto);
        assert_eq!(
            set_model(&mut scene, 5).unwrap_err(),
            "1 (ffr), 2 (segments), 3 (modal_segments), 4 (auto)"
        );
        assert!(set_reference(&mut scene, 0).is_err());
        assert!(set_reference(&mut scene, 4).is_ok());
        assert_eq!(scene.rod.reference, ReferenceKind::Cantilever);
    }

    #[test]
    fn policy_codes() {
        let mut scene = Scene::benchmark();
        for (code, policy) in [1, 2, 3].into_iter().zip(DeflectionPolicy::ALL) {
            assert_eq!(policy_code(policy), code);
            assert!(set_policy(&mut scene, code).is_ok());
            assert_eq!(scene.rod.deflection_policy, policy);
        }
        for bad in [0, 4, -1, i32::MIN] {
            assert_eq!(
                set_policy(&mut scene, bad).unwrap_err(),
                "1 (warn), 2 (discard) or 3 (error)"
            );
        }
    }

    #[test]
    fn element_counts() {
        assert_eq!(element_count(1), Ok(1));
        assert_eq!(element_count(ELEMENTS_MAX), Ok(MAX_ELEMENTS));
        assert!(element_count(0).is_err());
        assert!(element_count(ELEMENTS_MAX + 1).is_err());
        assert!(element_count(-3).is_err());
        assert!(non_negative(-1).is_err());
    }

    #[test]
    fn loaded_modes_codes() {
        let mut scene = Scene::benchmark();
        assert_eq!(loaded_modes_code(&scene), 0);
        assert!(set_loaded_modes(&mut scene, 1).is_ok());
        assert!(scene.rod.loaded_modes);
        assert_eq!(loaded_modes_code(&scene), 1);
        assert!(set_loaded_modes(&mut scene, 0).is_ok());
        assert!(!scene.rod.loaded_modes);
        for bad in [-1, 2, i32::MAX] {
            assert!(set_loaded_modes(&mut scene, bad)
                .unwrap_err()
                .starts_with("0 (free modes) or 1"));
        }
    }
}
