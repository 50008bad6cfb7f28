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
}

impl Model {
    /// The name in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Model::FfrLinear => "ffr_linear",
            Model::FfrStiffened => "ffr_stiffened",
            Model::Segments => "segments",
            Model::FfrRk4 => "ffr_stiffened_rk4",
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
            && (self.model == Model::FfrRk4 || self.rho_inf == other.rho_inf)
            && (self.model == Model::Segments
                || (self.modes == other.modes && self.reference == other.reference))
    }

    /// The setting of the default scene (`scenes/benchmark.toml`), its solver `auto` resolved
    /// the way the library resolves it.
    pub fn default_scene() -> Result<Setting, ModelError> {
        let scene = Scene::benchmark();
        let model = match scene.rod.model {
            RodModelKind::Segments => Model::Segments,
            RodModelKind::Ffr => {
                let simulation = Simulation::new(&scene)?;
                let explicit = simulation
                    .mechanism()
                    .integrator_name()
                    .0
                    .starts_with("RK4");
                match (scene.rod.axial_stiffening, explicit) {
                    (true, true) => Model::FfrRk4,
                    (true, false) => Model::FfrStiffened,
                    (false, false) => Model::FfrLinear,
                    (false, true) => {
                        return Err(ModelError::InvalidParameter {
                            name: "default scene",
                            value: 0.0,
                            allowed: "a setting the report has (RK4 with axial stiffening)".into(),
                        })
                    }
                }
            }
        };
        Ok(Setting {
            model,
            elements: scene.rod.elements,
            modes: scene.rod.modes,
            reference: scene.rod.reference,
            h: scene.solver.step,
            rho_inf: scene.solver.rho_inf,
        })
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
        s.experiment.crank_speed = case.speed();
        s.rod.elements = self.elements;
        s.solver.step = self.h;
        s.solver.rho_inf = self.rho_inf;
        // Each setting names its integrator (the benchmark scene's own is `auto`).
        s.solver.method = SolverMethod::GeneralizedAlpha;
        match self.model {
            Model::Segments => s.rod.model = RodModelKind::Segments,
            m => {
                s.rod.model = RodModelKind::Ffr;
                s.rod.modes = self.modes;
                s.rod.reference = self.reference;
                s.rod.axial_stiffening = m != Model::FfrLinear;
                if m == Model::FfrRk4 {
                    s.solver.method = SolverMethod::Rk4;
                }
            }
        }
        s
    }
}
