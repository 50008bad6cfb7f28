//! The crankshaft as a co-simulation model: its variables, the hooks an interface drives, and
//! its saved state.
//!
//! Variables (identifiers fixed per variable):
//!
//! | name | causality | unit | identifier |
//! |---|---|---|---|
//! | `drive.torque` | input | N.m | 1 |
//! | `load.torque` | input | N.m | 2 |
//! | `crank.angle` | output | rad | 10 |
//! | `crank.speed` | output | rad/s | 11 |
//! | `crank.acceleration` | output | rad/s2 | 12 |
//! | `crankshaft.inertia`, `.damping`, `.start_angle`, `.start_speed` | parameter | kg.m2, N.m.s, rad, rad/s | 100..103 |
//! | `time` (interfaces with an independent variable) | independent | s | 150 |
//!
//! With input derivatives, the first derivative of each torque at a communication point
//! makes the torque linear over the step; otherwise (and for orders above 1, which are
//! refused) it is held.
//!
//! The saved state's bytes, little endian: inertia, damping, start angle, start speed,
//! drive torque, load torque, drive torque rate, load torque rate f64, built u8 (+ time,
//! angle, speed f64), each value checked against its range when read.

use super::motion::{self, LinearTorque, Motion};
use super::scene::{
    CrankshaftScene, CrankshaftSpec, ANGLE_WINDOW, SPEED_WINDOW, TORQUE_RATE_WINDOW, TORQUE_WINDOW,
};
use crate::bytes::{ByteReader, ByteWriter};
use crate::cosimulation::units::SI_UNITS;
use crate::cosimulation::{
    Causality, CoSimulationModel, Declaration, Declarations, DefaultExperiment,
    InitialDependencies, Interface, ModelInfo, SavedState, StepOutcome, Value, ValueType,
    VariableId,
};
use crate::limits::EXPERIMENT_TIME_LIMIT;

const DRIVE_TORQUE: VariableId = 1;
const LOAD_TORQUE: VariableId = 2;
const ANGLE: VariableId = 10;
const SPEED: VariableId = 11;
const ACCELERATION: VariableId = 12;
const INERTIA: VariableId = 100;
const DAMPING: VariableId = 101;
const START_ANGLE: VariableId = 102;
const START_SPEED: VariableId = 103;
const TIME: VariableId = 150;

/// The inputs: the torques and their rates, N m and N m/s.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
struct Torques {
    drive: f64,
    load: f64,
    drive_rate: f64,
    load_rate: f64,
}

/// A started crankshaft: its time and motion.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Running {
    time: f64,
    motion: Motion,
}

/// A saved crankshaft.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Saved {
    spec: CrankshaftSpec,
    torques: Torques,
    running: Option<Running>,
}

/// One instance of the crankshaft.
pub struct CrankshaftModel {
    exported: CrankshaftSpec,
    spec: CrankshaftSpec,
    torques: Torques,
    running: Option<Running>,
    info: ModelInfo,
    declarations: Declarations,
}

fn real(unit: &'static str) -> ValueType {
    ValueType::Real {
        unit: Some(unit),
        display_unit: None,
    }
}

/// A variable of the crankshaft: outputs depend on every known during initialization
/// (the acceleration on the torques set), computed by the started model.
fn declaration(
    name: &str,
    vr: VariableId,
    causality: Causality,
    value_type: ValueType,
    start: Option<f64>,
    description: &str,
) -> Declaration {
    let output = causality == Causality::Output;
    Declaration {
        start: start.map(Value::Real),
        initial_dependencies: if output {
            InitialDependencies::All
        } else {
            InitialDependencies::None
        },
        computed: output,
        ..Declaration::new(name, vr, causality, value_type, description)
    }
}

fn declarations(spec: &CrankshaftSpec, interface: Interface) -> Declarations {
    let rad = ValueType::Real {
        unit: Some("rad"),
        display_unit: Some("deg"),
    };
    let rad_per_s = ValueType::Real {
        unit: Some("rad/s"),
        display_unit: Some("rpm"),
    };
    let torque_rate = if interface.input_derivatives {
        " (its first derivative at a communication point makes it linear over the step)"
    } else {
        " (held over the step)"
    };
    let mut list = vec![
        declaration(
            "drive.torque",
            DRIVE_TORQUE,
            Causality::Input,
            real("N.m"),
            Some(0.0),
            &format!("Torque the engine or motor applies to the crankshaft{torque_rate}"),
        ),
        declaration(
            "load.torque",
            LOAD_TORQUE,
            Causality::Input,
            real("N.m"),
            Some(0.0),
            &format!("Torque the load takes from the crankshaft, e.g. the rod FMU's crank.torque{torque_rate}"),
        ),
        declaration(
            "crank.angle",
            ANGLE,
            Causality::Output,
            rad,
            None,
            "Crank angle theta (counterclockwise)",
        ),
        declaration(
            "crank.speed",
            SPEED,
            Causality::Output,
            rad_per_s,
            None,
            "Crank speed omega = dtheta/dt",
        ),
        declaration(
            "crank.acceleration",
            ACCELERATION,
            Causality::Output,
            real("rad/s2"),
            None,
            "Crank acceleration (drive.torque - load.torque - damping omega) / inertia",
        ),
        declaration(
            "crankshaft.inertia",
            INERTIA,
            Causality::Parameter,
            real("kg.m2"),
            Some(spec.inertia),
            "Rotary inertia J of crankshaft and flywheel about the crank axis, in [1e-6, 1e6]",
        ),
        declaration(
            "crankshaft.damping",
            DAMPING,
            Causality::Parameter,
            real("N.m.s"),
            Some(spec.damping),
            "Viscous loss coefficient c (torque c omega per rad/s), in [0, 1e6]",
        ),
        declaration(
            "crankshaft.start_angle",
            START_ANGLE,
            Causality::Parameter,
            rad,
            Some(spec.start_angle),
            "Crank angle at the start time",
        ),
        declaration(
            "crankshaft.start_speed",
            START_SPEED,
            Causality::Parameter,
            rad_per_s,
            Some(spec.start_speed),
            "Crank speed at the start time, in [-1e4, 1e4]",
        ),
    ];
    for v in &mut list[5..7] {
        v.min = Some(Value::Real(0.0));
    }
    if interface.independent_variable {
        let time = declaration(
            "time",
            TIME,
            Causality::Independent,
            real("s"),
            None,
            "Simulation time",
        );
        list.insert(0, time);
    }
    Declarations::new(list, interface)
}

impl CrankshaftModel {
    /// The crankshaft of `scene` with its variables declared for `interface`.
    pub fn new(scene: CrankshaftScene, interface: Interface) -> Result<CrankshaftModel, String> {
        scene.validate().map_err(|e| e.to_string())?;
        let e = scene.experiment;
        let info = ModelInfo {
            name: scene.name.clone(),
            description: scene.description.clone(),
            default_experiment: DefaultExperiment {
                start_time: e.start_time,
                stop_time: e.stop_time,
                step_size: e.step_size,
            },
            units: SI_UNITS,
            enumeration_types: &[],
        };
        Ok(CrankshaftModel {
            declarations: declarations(&scene.crankshaft, interface),
            exported: scene.crankshaft,
            spec: scene.crankshaft,
            torques: Torques::default(),
            running: None,
            info,
        })
    }

    fn net_torque(&self) -> LinearTorque {
        LinearTorque {
            value: self.torques.drive - self.torques.load,
            rate: self.torques.drive_rate - self.torques.load_rate,
        }
    }

    fn name(&self, vr: VariableId) -> &str {
        self.declarations.get(vr).map_or("?", |v| v.name.as_str())
    }
}

/// `|x| <= window`, finite; else the allowed range as text.
fn within(x: f64, window: f64) -> Result<(), String> {
    if x.is_finite() && x.abs() <= window {
        Ok(())
    } else {
        Err(format!(
            "a finite value with |value| <= {window:e} in SI units"
        ))
    }
}

impl CoSimulationModel for CrankshaftModel {
    fn info(&self) -> &ModelInfo {
        &self.info
    }

    fn declarations(&self) -> &Declarations {
        &self.declarations
    }

    fn accuracy_note(&self) -> String {
        "the motion is exact for torques linear over each step (no tolerance applies)".into()
    }

    fn time(&self) -> Option<f64> {
        self.running.map(|r| r.time)
    }

    fn is_built(&self) -> bool {
        self.running.is_some()
    }

    fn invalidate(&mut self, _parameter_changed: bool) {
        self.running = None;
    }

    fn discard_built(&mut self) {
        self.running = None;
    }

    fn ensure_started(&mut self, start_time: f64) -> Result<(), String> {
        if self.running.is_none() {
            self.spec.validate().map_err(|e| e.to_string())?;
            self.running = Some(Running {
                time: start_time,
                motion: Motion {
                    angle: self.spec.start_angle,
                    speed: self.spec.start_speed,
                },
            });
        }
        Ok(())
    }

    fn begin_stepping(&mut self) {}

    fn start_summary(&self) -> String {
        let speed = self
            .running
            .map_or(self.spec.start_speed, |r| r.motion.speed);
        format!(
            "crank.speed = {speed} rad/s, inertia {} kg m^2, damping {} N m s/rad",
            self.spec.inertia, self.spec.damping
        )
    }

    fn get_real(&self, vr: VariableId, out: &mut [f64], start_time: f64) -> Result<(), String> {
        let s = &self.spec;
        let motion = self.running.map(|r| r.motion);
        let moving = || motion.ok_or_else(|| format!("{} needs the model started", self.name(vr)));
        out[0] = match vr {
            DRIVE_TORQUE => self.torques.drive,
            LOAD_TORQUE => self.torques.load,
            ANGLE => moving()?.angle,
            SPEED => moving()?.speed,
            ACCELERATION => motion::acceleration(
                moving()?.speed,
                self.net_torque().value,
                s.inertia,
                s.damping,
            ),
            INERTIA => s.inertia,
            DAMPING => s.damping,
            START_ANGLE => s.start_angle,
            START_SPEED => s.start_speed,
            TIME => self.time().unwrap_or(start_time),
            _ => return Err(format!("unknown value reference {vr}")),
        };
        Ok(())
    }

    fn get_integer(&self, vr: VariableId) -> Result<i32, String> {
        Err(format!("{} is not an Integer variable", self.name(vr)))
    }

    fn check_real(&self, vr: VariableId, x: f64) -> Result<(), String> {
        let (low, high) = match vr {
            DRIVE_TORQUE | LOAD_TORQUE => (-TORQUE_WINDOW, TORQUE_WINDOW),
            INERTIA => super::scene::INERTIA_RANGE,
            DAMPING => super::scene::DAMPING_RANGE,
            START_ANGLE => (-ANGLE_WINDOW, ANGLE_WINDOW),
            START_SPEED => (-SPEED_WINDOW, SPEED_WINDOW),
            _ => return Err(format!("{} cannot be set", self.name(vr))),
        };
        if (low..=high).contains(&x) {
            Ok(())
        } else {
            Err(format!("a value in [{low:e}, {high:e}] in SI units"))
        }
    }

    fn set_real(&mut self, vr: VariableId, x: f64) -> Result<bool, String> {
        self.check_real(vr, x)?;
        let s = &mut self.spec;
        match vr {
            DRIVE_TORQUE => {
                self.torques.drive = x;
                self.torques.drive_rate = 0.0;
                return Ok(false);
            }
            LOAD_TORQUE => {
                self.torques.load = x;
                self.torques.load_rate = 0.0;
                return Ok(false);
            }
            INERTIA => s.inertia = x,
            DAMPING => s.damping = x,
            START_ANGLE => s.start_angle = x,
            _ => s.start_speed = x,
        }
        Ok(true)
    }

    fn set_integers(&mut self, items: &[(VariableId, i32)]) -> Result<(), (usize, String)> {
        match items.first() {
            None => Ok(()),
            Some(&(vr, _)) => Err((0, format!("{} is not an Integer variable", self.name(vr)))),
        }
    }

    fn check_input_derivative(&self, vr: VariableId, order: i32, x: f64) -> Result<(), String> {
        if !matches!(vr, DRIVE_TORQUE | LOAD_TORQUE) {
            return Err(format!(
                "{} (value reference {vr}) is not an input: derivatives are set only for drive.torque and load.torque",
                self.name(vr)
            ));
        }
        if order != 1 {
            return Err(format!(
                "order = {order} for {} is not supported: allowed 1 (the torque is linear over a step)",
                self.name(vr)
            ));
        }
        within(x, TORQUE_RATE_WINDOW).map_err(|allowed| {
            format!(
                "the derivative of {} = {x:e}: allowed {allowed}",
                self.name(vr)
            )
        })
    }

    fn set_input_derivatives(
        &mut self,
        items: &[(VariableId, i32, f64)],
    ) -> Result<Vec<String>, String> {
        for &(vr, order, x) in items {
            self.check_input_derivative(vr, order, x)?;
        }
        for &(vr, _, x) in items {
            if vr == DRIVE_TORQUE {
                self.torques.drive_rate = x;
            } else {
                self.torques.load_rate = x;
            }
        }
        Ok(Vec::new())
    }

    fn step(&mut self, h: f64) -> StepOutcome {
        let Some(running) = self.running else {
            return StepOutcome::Failed("the model was not started (internal error)".into());
        };
        let s = self.spec;
        let next = motion::advance(running.motion, self.net_torque(), s.inertia, s.damping, h);
        if within(next.speed, SPEED_WINDOW).is_err() || within(next.angle, ANGLE_WINDOW).is_err() {
            return StepOutcome::Refused(format!(
                "the step of {h:e} s would leave crank.speed = {:e} rad/s, crank.angle = {:e} rad: allowed |crank.speed| <= {SPEED_WINDOW:e} rad/s and |crank.angle| <= {ANGLE_WINDOW:e} rad; nothing changed",
                next.speed, next.angle
            ));
        }
        self.running = Some(Running {
            time: running.time + h,
            motion: next,
        });
        // The torque's rate applies from this communication point on; at the next one the
        // torque is the value set there (a new law starts).
        self.torques.drive += self.torques.drive_rate * h;
        self.torques.load += self.torques.load_rate * h;
        self.torques.drive = self.torques.drive.clamp(-TORQUE_WINDOW, TORQUE_WINDOW);
        self.torques.load = self.torques.load.clamp(-TORQUE_WINDOW, TORQUE_WINDOW);
        StepOutcome::Done
    }

    fn take_warnings(&mut self) -> Vec<String> {
        Vec::new()
    }

    fn reset(&mut self) {
        self.spec = self.exported;
        self.torques = Torques::default();
        self.running = None;
    }

    fn save(&self) -> SavedState {
        Box::new(Saved {
            spec: self.spec,
            torques: self.torques,
            running: self.running,
        })
    }

    fn restore(&mut self, state: &SavedState) -> Result<(), String> {
        let saved = saved(state)?;
        self.spec = saved.spec;
        self.torques = saved.torques;
        self.running = saved.running;
        Ok(())
    }

    fn saved_time(&self, state: &SavedState) -> Option<f64> {
        saved(state).ok()?.running.map(|r| r.time)
    }

    fn write_saved(&mut self, state: &SavedState) -> Result<Vec<u8>, String> {
        let saved = saved(state)?;
        let mut w = ByteWriter::default();
        let (s, t) = (&saved.spec, &saved.torques);
        for x in [s.inertia, s.damping, s.start_angle, s.start_speed] {
            w.f64(x);
        }
        for x in [t.drive, t.load, t.drive_rate, t.load_rate] {
            w.f64(x);
        }
        w.flag(saved.running.is_some());
        if let Some(r) = saved.running {
            for x in [r.time, r.motion.angle, r.motion.speed] {
                w.f64(x);
            }
        }
        Ok(w.bytes)
    }

    fn read_saved(&mut self, bytes: &[u8]) -> Result<SavedState, String> {
        let mut r = ByteReader::new(bytes);
        let spec = CrankshaftSpec {
            inertia: r.f64("crankshaft.inertia")?,
            damping: r.f64("crankshaft.damping")?,
            start_angle: r.f64("crankshaft.start_angle")?,
            start_speed: r.f64("crankshaft.start_speed")?,
        };
        spec.validate().map_err(|e| e.to_string())?;
        let mut torques = [0.0; 4];
        for (x, (name, window)) in torques.iter_mut().zip([
            ("drive.torque", TORQUE_WINDOW),
            ("load.torque", TORQUE_WINDOW),
            ("the rate of drive.torque", TORQUE_RATE_WINDOW),
            ("the rate of load.torque", TORQUE_RATE_WINDOW),
        ]) {
            *x = r.f64(name)?;
            within(*x, window).map_err(|allowed| format!("{name} = {x:e}: allowed {allowed}"))?;
        }
        let running = if r.flag("the started flag")? {
            let time = r.f64("the time")?;
            let angle = r.f64("crank.angle")?;
            let speed = r.f64("crank.speed")?;
            within(time, EXPERIMENT_TIME_LIMIT)
                .map_err(|allowed| format!("the time = {time:e}: allowed {allowed}"))?;
            within(angle, ANGLE_WINDOW)
                .map_err(|allowed| format!("crank.angle = {angle:e}: allowed {allowed}"))?;
            within(speed, SPEED_WINDOW)
                .map_err(|allowed| format!("crank.speed = {speed:e}: allowed {allowed}"))?;
            Some(Running {
                time,
                motion: Motion { angle, speed },
            })
        } else {
            None
        };
        r.finish("the crankshaft's state")?;
        let [drive, load, drive_rate, load_rate] = torques;
        Ok(Box::new(Saved {
            spec,
            torques: Torques {
                drive,
                load,
                drive_rate,
                load_rate,
            },
            running,
        }))
    }
}

fn saved(state: &SavedState) -> Result<&Saved, String> {
    state
        .downcast_ref::<Saved>()
        .ok_or_else(|| "the saved state is not a state of the crankshaft".to_string())
}
