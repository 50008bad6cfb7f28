//! Helpers shared by the integration tests (each test file includes them with `mod common;`).
//!
//! - [`runs`]: driving a scene through `flexrod::drive` and measuring a run (peaks, pointwise
//!   differences), including runs that may end in a failed step;
//! - [`exudyn`]: the geometrically exact reference, `tests/data/exudyn_ancf_150rad_s.csv`;
//! - [`published_frequencies`]: the frequency tables of Agrawal and Shabana (1985) and of the
//!   CDI benchmark note;
//! - [`fragments`]: the generated-fragment convention (`docs/generated/<id>.md` embedded in
//!   README.md and docs/ between markers) and [`check_generated`];
//! - [`child`]: child processes with a time limit;
//! - [`generated`]: tables assembled from parts measured by several tests, number formats;
//! - [`summary`]: what a printed summary of a scene may and must say (the scene's words).

// Not every test file uses every helper.
#![allow(dead_code)]

pub mod child;
pub mod exudyn;
pub mod fragments;
pub mod generated;
pub mod published_frequencies;
pub mod runs;
pub mod summary;

#[allow(unused_imports)]
pub use fragments::{
    blessing, check_generated, fragment_path, generated_dir, is_fragment_id, line_diff, repository,
};

/// The default scene with the Euler-Bernoulli FFR rod forced (`rod.model = "ffr"`, `rod.shear_deformation = "off"`): the
/// scene of the tests that compare with Euler-Bernoulli references (closed-form frequency
/// equations, the ANCF cable, the published tables), so that like is compared with like
/// (`auto` puts shear deformation and rotary inertia into the benchmark rod, whose slenderness
/// L / h = 55 changes v_mid by about 2e-3 with them).
pub fn euler_bernoulli_benchmark() -> flexrod::Scene {
    let mut s = flexrod::Scene::benchmark();
    s.rod.model = flexrod::rod::RodModelKind::Ffr;
    s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
    s
}
