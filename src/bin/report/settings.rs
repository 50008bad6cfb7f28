//! A setting: rod model, elements, modes, reference conditions, solver step and rho_inf; how it
//! is named in the tables and which scene it runs. The matrix of settings is in [`matrix`].

mod matrix;

pub use matrix::{matrix, reference_setting};

use flexrod::scene::{ReferenceKind, RodModelKind, SolverMethod};
use flexrod::{ModelError, Scene, Simulation};

use crate::cases::Case;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Model {
    FfrLinear,
    FfrStiffened,
    Segments,
    /// FFR with axial stiffening, explicit RK4 with projection (`solver.method = "rk4"`).
    FfrRk4,
    /// FFR with axial stiffening, error-controlled (`solver.method = "auto"`: RK4(3) on the
    /// closed-form minimal coordinates, its exponential form where the modes leave the pins in
    /// place); `h` of the setting is `solver.tolerance`.
    FfrAuto,
    /// The segment chain, error-controlled (`auto`: adaptive generalized-alpha); `h` is the
    /// tolerance.
    SegmentsAuto,
    /// FFR with axial stiffening, `solver.method = "dopri5"`: Dormand-Prince 5(4) on the
    /// closed-form minimal coordinates; `h` is the tolerance.
    FfrDopri5,
    /// The segment chain on its lowest modes (`rod.model = "modal_segments"`, shear off as in
    /// the reference chain), `auto` (the exponential RK4(3)); `h` is the tolerance.
    ModalSegmentsAuto,
}

impl Model {
    /// The name in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Model::FfrLinear => "ffr_linear",
            Model::FfrStiffened => "ffr_stiffened",
            Model::Segments => "segments",
            Model::FfrRk4 => "ffr_stiffened_rk4",
            Model::FfrAuto => "ffr_stiffened_auto",
            Model::SegmentsAuto => "segments_auto",
            Model::FfrDopri5 => "ffr_stiffened_dopri5",
            Model::ModalSegmentsAuto => "modal_segments_auto",
        }
    }

    /// The series of the figure.
    pub fn index(self) -> usize {
        self as usize
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    pub model: Model,
    pub elements: usize,
    pub modes: usize,
    pub reference: ReferenceKind,
    pub h: f64,
    pub rho_inf: f64,
}

/// The name of reference conditions in the CSV.
pub fn reference_name(r: ReferenceKind) -> &'static str {
    match r {
        ReferenceKind::SimplySupported => "simply_supported",
        ReferenceKind::MeanAxis => "mean_axis",
        ReferenceKind::BodyFixedMid => "body_fixed_mid",
        ReferenceKind::Cantilever => "cantilever",
    }
}

impl Setting {
    pub fn ffr(stiff: bool, elements: usize, modes: usize, h: f64) -> Setting {
        Setting {
            model: if stiff {
                Model::FfrStiffened
            } else {
                Model::FfrLinear
            },
            elements,
            modes,
            reference: ReferenceKind::SimplySupported,
            h,
            rho_inf: 0.8,
        }
    }

    pub fn rk4(elements: usize, modes: usize, h: f64) -> Setting {
        Setting {
            model: Model::FfrRk4,
            ..Setting::ffr(true, elements, modes, h)
        }
    }

    /// Error-controlled FFR (stiffened) with `solver.tolerance = tolerance`.
    pub fn auto(elements: usize, modes: usize, tolerance: f64) -> Setting {
        Setting {
            model: Model::FfrAuto,
            ..Setting::ffr(true, elements, modes, tolerance)
        }
    }

    /// Dormand-Prince (`solver.method = "dopri5"`) with `solver.tolerance = tolerance`.
    pub fn dopri5(elements: usize, modes: usize, tolerance: f64) -> Setting {
        Setting {
            model: Model::FfrDopri5,
            ..Setting::ffr(true, elements, modes, tolerance)
        }
    }

    /// Error-controlled segment chain with `solver.tolerance = tolerance`.
    pub fn seg_auto(n: usize, tolerance: f64) -> Setting {
        Setting {
            model: Model::SegmentsAuto,
            ..Setting::seg(n, tolerance)
        }
    }

    /// The chain of `n` segments on its `modes` lowest modes, `auto` at `tolerance`.
    pub fn modal_auto(n: usize, modes: usize, tolerance: f64) -> Setting {
        Setting {
            model: Model::ModalSegmentsAuto,
            modes,
            ..Setting::seg(n, tolerance)
        }
    }

    pub fn seg(n: usize, h: f64) -> Setting {
        Setting {
            model: Model::Segments,
            elements: n,
            modes: 0,
            reference: ReferenceKind::SimplySupported,
            h,
            rho_inf: 0.8,
        }
    }

    pub fn rho(mut self, rho: f64) -> Setting {
        self.rho_inf = rho;
        self
    }

    pub fn with_reference(mut self, r: ReferenceKind) -> Setting {
        self.reference = r;
        self
    }

    /// Whether `self` and `other` run the same computation (rho_inf does not matter to RK4,
    /// modes and reference conditions not to the segment chain).
    pub fn same_run(&self, other: &Setting) -> bool {
        self.model == other.model
            && self.elements == other.elements
            && self.h == other.h
            && (matches!(self.model, Model::FfrRk4 | Model::FfrDopri5)
                || self.rho_inf == other.rho_inf)
            && (matches!(self.model, Model::Segments | Model::SegmentsAuto)
                || (self.modes == other.modes && self.reference == other.reference))
    }

    /// The setting of the default scene (`scenes/benchmark.toml`): its solver is `auto`, so
    /// the error-controlled setting of its model at its tolerance.
    pub fn default_scene() -> Result<Setting, ModelError> {
        let scene = Scene::benchmark();
        // The rod model built (`auto` at the scene's crank speed).
        let built = Simulation::new(&scene)?.mechanism().spec.rod.model;
        let model = match (built, scene.solver.method, scene.rod.axial_stiffening) {
            (RodModelKind::Segments, SolverMethod::Auto, _) => Model::SegmentsAuto,
            (RodModelKind::Ffr, SolverMethod::Auto, true) => Model::FfrAuto,
            _ => {
                return Err(ModelError::InvalidParameter {
                    name: "default scene",
                    value: 0.0,
                    allowed: "solver.method = auto (with axial stiffening for the FFR rod)".into(),
                })
            }
        };
        Ok(Setting {
            model,
            elements: scene.rod.elements,
            modes: scene.rod.modes,
            reference: scene.rod.reference,
            h: scene.solver.tolerance,
            rho_inf: scene.solver.rho_inf,
        })
    }

    /// The communication step the report samples this setting at: its solver step, or for the
    /// error-controlled settings (whose `h` is the tolerance) 3e-4 s, the default scene's.
    pub fn communication_step(&self) -> f64 {
        match self.model {
            Model::FfrAuto | Model::SegmentsAuto | Model::FfrDopri5 | Model::ModalSegmentsAuto => {
                3e-4
            }
            _ => self.h,
        }
    }

    pub fn label(&self) -> String {
        let r = match self.reference {
            ReferenceKind::SimplySupported => "ss",
            ReferenceKind::MeanAxis => "mean-axis",
            ReferenceKind::BodyFixedMid => "fixed-mid",
            ReferenceKind::Cantilever => "cantilever",
        };
        let (el, modes, h, rho) = (self.elements, self.modes, self.h, self.rho_inf);
        match self.model {
            Model::Segments => format!("segments N={el} h={h:.0e} rho={rho}"),
            Model::FfrRk4 => format!("FFR stiffened RK4 {el}el/{modes}m {r} h={h:.1e}"),
            Model::FfrAuto => format!("FFR stiffened auto {el}el/{modes}m {r} tol={h:.0e}"),
            Model::SegmentsAuto => format!("segments auto N={el} tol={h:.0e}"),
            Model::ModalSegmentsAuto => {
                format!("modal segments auto N={el} rod.modes={modes} tol={h:.0e}")
            }
            Model::FfrDopri5 => {
                format!("FFR stiffened Dormand-Prince {el}el/{modes}m {r} tol={h:.0e}")
            }
            Model::FfrLinear => format!("FFR linear {el}el/{modes}m {r} h={h:.0e} rho={rho}"),
            Model::FfrStiffened => {
                format!("FFR stiffened {el}el/{modes}m {r} h={h:.0e} rho={rho}")
            }
        }
    }

    /// The benchmark scene with this setting, for `case`.
    pub fn scene(&self, case: &Case) -> Scene {
        let mut s = Scene::benchmark();
        s.slider.mass = case.slider_mass;
        s.rod.deflection_policy = case.deflection_policy;
        s.experiment.crank_speed = case.speed();
        s.rod.elements = self.elements;
        s.solver.step = self.h;
        s.solver.rho_inf = self.rho_inf;
        // Each setting names its integrator (the benchmark scene's own is `auto`).
        s.solver.method = SolverMethod::GeneralizedAlpha;
        match self.model {
            Model::Segments => s.rod.model = RodModelKind::Segments,
            Model::SegmentsAuto => {
                s.rod.model = RodModelKind::Segments;
                s.solver.method = SolverMethod::Auto;
                s.solver.step = 3e-4;
                s.solver.tolerance = self.h;
            }
            Model::ModalSegmentsAuto => {
                // The reference chain's physics (Euler-Bernoulli, as the chain's `auto` keeps
                // it): like with like.
                s.rod.model = RodModelKind::ModalSegments;
                s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
                s.rod.modes = self.modes;
                s.solver.method = SolverMethod::Auto;
                s.solver.step = 3e-4;
                s.solver.tolerance = self.h;
            }
            m => {
                s.rod.model = RodModelKind::Ffr;
                s.rod.modes = self.modes;
                s.rod.reference = self.reference;
                s.rod.axial_stiffening = m != Model::FfrLinear;
                if m == Model::FfrRk4 {
                    s.solver.method = SolverMethod::Rk4;
                }
                if m == Model::FfrDopri5 {
                    s.solver.method = SolverMethod::Dopri5;
                    s.solver.step = 3e-4;
                    s.solver.tolerance = self.h;
                }
                if m == Model::FfrAuto {
                    s.solver.method = SolverMethod::Auto;
                    s.solver.step = 3e-4;
                    s.solver.tolerance = self.h;
                }
            }
        }
        s
    }
}
