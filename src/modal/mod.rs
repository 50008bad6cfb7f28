//! Component modes of the rod (O. P. Agrawal and A. A. Shabana, "Dynamic analysis of multibody
//! systems using component modes", *Computers & Structures* 21(6), 1985, sections 3 and 4):
//! reference conditions `q_f = B_r q_r` (eq. 3.9), the eigenproblem `K_rr a = w^2 M_rr a`
//! (eq. 4.4), mass-loaded modes ([`mass_loaded_modes`]), mode selection, and the inertia shape
//! integrals of the retained modes (the "preprocessor" of that paper, Fig. 4).

pub mod axial_coupling;
pub mod component_modes;
pub mod eigen;
pub mod mass_loaded_modes;
pub mod reference;
pub mod selection;
pub mod shape_integrals;

pub use component_modes::ComponentModes;
pub use reference::{ReferenceConditions, ReferenceKind};
pub use selection::ModeSelection;
pub use shape_integrals::ShapeIntegrals;
