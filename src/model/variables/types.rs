//! A variable of the rod's model: its declaration (what an interface sees, see
//! [`crate::cosimulation`]) and where its value lives ([`Access`]).

use std::ops::{Deref, DerefMut};

use crate::cosimulation::Declaration;
use crate::mechanism::Outputs;
use crate::scene::Scene;
use crate::simulation::Simulation;

/// The inputs an instance stores between communication points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputSlot {
    CrankAngle,
    CrankSpeed,
    SliderForce,
    /// The crank acceleration `alpha_k` of the input law, as an input of its own (for
    /// interfaces without input derivatives, see [`super::Interface`]).
    CrankAcceleration,
    /// The crank jerk `j_k` of the input law, as an input of its own (the same interfaces).
    CrankJerk,
}

/// Reads one output from the simulation's outputs.
pub type OutputGetter = fn(&Outputs) -> f64;

/// Where a variable's value lives and how to read or write it.
#[derive(Clone, Copy)]
pub enum Access {
    /// An input kept by the instance.
    Input(InputSlot),
    /// An output of the simulation.
    Output(OutputGetter),
    /// A Real parameter stored in the instance's scene. `applied`: where the model resolves the
    /// value when it is built (a default that depends on what `auto` settings chose), the value
    /// that applies, read from the built simulation.
    RealParameter {
        get: fn(&Scene) -> f64,
        set: fn(&mut Scene, f64),
        applied: Option<fn(&Simulation) -> f64>,
    },
    /// An Integer or Enumeration parameter stored in the instance's scene. `set` returns
    /// the allowed range when the value cannot be stored.
    IntegerParameter {
        get: fn(&Scene) -> i32,
        set: fn(&mut Scene, i32) -> Result<(), String>,
    },
    /// `rod.frequency[k]`: index k - 1 into `Simulation::frequencies_hz`.
    Frequency(usize),
    /// `rod.mass`: the rod with its end bodies, from the instance's scene.
    RodMass,
    /// `time`, the independent variable: the model's time.
    Time,
    /// The array `rod.shape`: the transverse deflection at equally spaced points.
    Shape,
    /// The array `rod.frequency`: the first `len` natural frequencies, Hz.
    Frequencies,
}

/// One variable: its declaration and where its value lives. It reads as its declaration
/// (`v.name`, `v.causality`, ...).
#[derive(Clone)]
pub struct Variable {
    pub declared: Declaration,
    pub access: Access,
}

impl Deref for Variable {
    type Target = Declaration;
    fn deref(&self) -> &Declaration {
        &self.declared
    }
}

impl DerefMut for Variable {
    fn deref_mut(&mut self) -> &mut Declaration {
        &mut self.declared
    }
}

impl Access {
    /// The value comes from the simulation (outputs, frequencies, the shape), which must be
    /// built and started to read it.
    pub fn needs_simulation(self) -> bool {
        matches!(
            self,
            Access::Output(_) | Access::Frequency(_) | Access::Frequencies | Access::Shape
        )
    }
}
