//! The model's enumeration types. Their items are the core's single name lists
//! (`RodModelKind::ALL`, `ReferenceKind::ALL` with `name()`), numbered 1, 2, ... in that
//! order; only the items' descriptions are written here.

use crate::cosimulation::{EnumerationItem, EnumerationType};
use crate::rod::PhysicsSwitch;
use crate::scene::{ReferenceKind, RodModelKind};

/// A core enumeration exported as an enumeration type: its variants in code order.
pub trait Kind: Copy + PartialEq + 'static {
    /// Every variant; the code of `ALL[i]` is `i + 1`.
    const ALL: &'static [Self];
    /// The name in scenes and in descriptions.
    fn name(self) -> &'static str;
    /// The item's description.
    fn description(self) -> &'static str;
}

impl Kind for RodModelKind {
    const ALL: &'static [Self] = &RodModelKind::ALL;
    fn name(self) -> &'static str {
        RodModelKind::name(self)
    }
    fn description(self) -> &'static str {
        match self {
            RodModelKind::Ffr => "Floating frame of reference with component modes",
            RodModelKind::Segments => {
                "Rigid segments joined by rotational springs (finite segment method)"
            }
            RodModelKind::ModalSegments => {
                "The segment chain on its lowest bending modes (exact kinematics, few coordinates)"
            }
            RodModelKind::Auto => {
                "The FFR rod, or the segment chain on its modes where the predicted deflection at crank.design_speed calls for exact kinematics"
            }
        }
    }
}

impl Kind for ReferenceKind {
    const ALL: &'static [Self] = &ReferenceKind::ALL;
    fn name(self) -> &'static str {
        ReferenceKind::name(self)
    }
    fn description(self) -> &'static str {
        match self {
            ReferenceKind::SimplySupported => {
                "u = v = 0 at B, v = 0 at C; frame at B, x axis through C"
            }
            ReferenceKind::MeanAxis => {
                "Free-free modes without the rigid-body modes; frame at the centre of mass"
            }
            ReferenceKind::BodyFixedMid => {
                "All coordinates of the middle node zero (even number of elements)"
            }
            ReferenceKind::Cantilever => "All coordinates of the B node zero",
        }
    }
}

impl Kind for PhysicsSwitch {
    const ALL: &'static [Self] = &PhysicsSwitch::ALL;
    fn name(self) -> &'static str {
        PhysicsSwitch::name(self)
    }
    fn description(self) -> &'static str {
        match self {
            PhysicsSwitch::Auto => {
                "Chosen at initialization from the rod's numbers and solver.tolerance (logged)"
            }
            PhysicsSwitch::On => "In the model",
            PhysicsSwitch::Off => "Left out",
        }
    }
}

/// The code (1-based) of a variant.
pub fn code<K: Kind>(kind: K) -> i32 {
    let position = K::ALL.iter().position(|&k| k == kind).unwrap_or(0);
    i32::try_from(position + 1).unwrap_or(i32::MAX)
}

/// The variant of a code, `None` outside 1..=ALL.len().
pub fn from_code<K: Kind>(code: i32) -> Option<K> {
    let index = usize::try_from(code).ok()?.checked_sub(1)?;
    K::ALL.get(index).copied()
}

fn items<K: Kind>() -> Vec<EnumerationItem> {
    K::ALL
        .iter()
        .map(|&k| EnumerationItem {
            name: k.name(),
            description: k.description(),
        })
        .collect()
}

/// `rod.model`.
pub static ROD_MODEL: EnumerationType = EnumerationType {
    name: "RodModel",
    description: "Which model computes the connecting rod",
    items: items::<RodModelKind>,
};

/// `rod.reference`.
pub static ROD_REFERENCE: EnumerationType = EnumerationType {
    name: "RodReference",
    description: "Reference conditions of the FFR rod",
    items: items::<ReferenceKind>,
};

/// `rod.shear_deformation`, `rod.axial_dynamics`.
pub static PHYSICS_SWITCH: EnumerationType = EnumerationType {
    name: "PhysicsSwitch",
    description: "A part of the rod's physics: chosen by the model (auto), on or off",
    items: items::<PhysicsSwitch>,
};

/// Every enumeration type, in `TypeDefinitions` order.
pub static ENUMERATION_TYPES: [&EnumerationType; 3] = [&ROD_MODEL, &ROD_REFERENCE, &PHYSICS_SWITCH];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_follow_the_core_lists() {
        for (i, &k) in ReferenceKind::ALL.iter().enumerate() {
            assert_eq!(code(k), i as i32 + 1);
            assert_eq!(from_code::<ReferenceKind>(code(k)), Some(k));
            assert_eq!(ROD_REFERENCE.items()[i].name, k.name());
        }
        assert_eq!(from_code::<RodModelKind>(0), None);
        assert_eq!(
            from_code::<RodModelKind>(3),
            Some(RodModelKind::ModalSegments)
        );
        assert_eq!(from_code::<RodModelKind>(4), Some(RodModelKind::Auto));
        assert_eq!(from_code::<RodModelKind>(5), None);
        assert_eq!(from_code::<RodModelKind>(-1), None);
        assert_eq!(
            ROD_MODEL.allowed_text(),
            "1 (ffr), 2 (segments), 3 (modal_segments), 4 (auto)"
        );
        assert_eq!(
            ROD_MODEL.codes_text(),
            "1 = ffr, 2 = segments, 3 = modal_segments, 4 = auto"
        );
        assert_eq!(ROD_REFERENCE.max_code(), 4);
    }
}
