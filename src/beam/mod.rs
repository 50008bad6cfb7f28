//! Planar Euler-Bernoulli beam: section properties, the element, Gauss quadrature, and the
//! assembly of a straight rod (seed 001, "Deformable connecting rod"; Shabana, *Dynamics of
//! Multibody Systems*, 4th ed., ch. 6).

pub mod element;
pub mod mesh;
pub mod quadrature;
pub mod section;

pub use element::{BeamElement, MassKind};
pub use mesh::RodMesh;
pub use section::RodProperties;
