//! Planar beam (Euler-Bernoulli, or shear-deformable with a varying section): section
//! properties and tables, the elements, Gauss quadrature, and the
//! assembly of a straight rod (the CDI benchmark note, "Deformable connecting rod"; Shabana, *Dynamics of
//! Multibody Systems*, 4th ed., ch. 6).

pub mod definition;
pub mod element;
pub mod mesh;
pub mod quadrature;
pub mod section;
pub mod section_element;
pub mod section_table;

pub use definition::RodDefinition;
pub use element::{BeamElement, MassKind};
pub use mesh::RodMesh;
pub use section::RodProperties;
pub use section_element::SectionElement;
pub use section_table::{EndBody, SectionStation, SectionTable, SectionValues};
