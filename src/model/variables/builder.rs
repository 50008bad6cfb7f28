//! The builder of the variable list: one method per kind of variable (input, output, Real or
//! Integer parameter, calculated parameter), and the unit types the list uses.

use super::types::{Access, InputSlot, OutputGetter, Variable};
use super::{Interface, VariableId, VariableTable};
use crate::cosimulation::{Causality, Declaration, InitialDependencies, Value, ValueType};
use crate::scene::Scene;

pub(super) const RAD: ValueType = ValueType::Real {
    unit: Some("rad"),
    display_unit: Some("deg"),
};
pub(super) const RAD_PER_S: ValueType = ValueType::Real {
    unit: Some("rad/s"),
    display_unit: Some("rpm"),
};

pub(super) const fn real(unit: &'static str) -> ValueType {
    ValueType::Real {
        unit: Some(unit),
        display_unit: None,
    }
}

pub(super) const DIMENSIONLESS: ValueType = ValueType::Real {
    unit: None,
    display_unit: None,
};

/// Collects the variables of one table, in description order.
pub(super) struct Builder<'a> {
    pub scene: &'a Scene,
    interface: Interface,
    variables: Vec<Variable>,
}

impl<'a> Builder<'a> {
    pub fn new(scene: &'a Scene, interface: Interface) -> Builder<'a> {
        Builder {
            scene,
            interface,
            variables: Vec::new(),
        }
    }

    /// The interface the table is declared for.
    pub fn interface(&self) -> Interface {
        self.interface
    }

    /// The table, with its index by value reference.
    pub fn finish(self) -> VariableTable {
        VariableTable::from_variables(self.variables, self.interface)
    }

    /// Add a variable; `computed` follows from where its value lives.
    fn push(&mut self, declared: Declaration, access: Access) {
        let declared = Declaration {
            computed: access.needs_simulation(),
            ..declared
        };
        self.variables.push(Variable { declared, access });
    }

    /// `min`/`max` of the variable added last.
    pub fn bounds(&mut self, min: Option<Value>, max: Option<Value>) {
        if let Some(v) = self.variables.last_mut() {
            v.min = min;
            v.max = max;
        }
    }

    /// Replace the description of the variable `name` (for a text that differs between the
    /// standards).
    pub fn describe(&mut self, name: &str, description: &str) {
        if let Some(v) = self.variables.iter_mut().find(|v| v.name == name) {
            v.description = description.into();
        }
    }

    /// Replace the access of the variable added last.
    pub fn set_access(&mut self, access: Access) {
        if let Some(v) = self.variables.last_mut() {
            v.access = access;
            v.declared.computed = access.needs_simulation();
        }
    }

    /// The Real parameter added last reads, once the model is built, the value that applies
    /// (see [`Access::RealParameter`]).
    pub fn applied(&mut self, applied: fn(&crate::simulation::Simulation) -> f64) {
        if let Some(v) = self.variables.last_mut() {
            if let Access::RealParameter { applied: a, .. } = &mut v.access {
                *a = Some(applied);
            }
        }
    }

    /// Make the variable added last an array of `n` elements.
    pub fn array(&mut self, n: usize) {
        if let Some(v) = self.variables.last_mut() {
            v.dimension = Some(n);
        }
    }

    /// The independent variable `time` (causality `independent`).
    pub fn independent(&mut self, name: &str, vr: VariableId, description: &str) {
        self.push(
            Declaration::new(name, vr, Causality::Independent, real("s"), description),
            Access::Time,
        );
    }

    /// `min="0"` on a Real parameter that must be positive: the bounds are closed, so 0
    /// itself passes the declared range and is rejected when the model is built (at the end
    /// of initialization, naming the parameter).
    pub fn positive(&mut self) {
        self.bounds(Some(Value::Real(0.0)), None);
    }

    /// `min="0"`: zero allowed.
    pub fn non_negative(&mut self) {
        self.bounds(Some(Value::Real(0.0)), None);
    }

    pub fn input(
        &mut self,
        name: &str,
        vr: VariableId,
        ty: ValueType,
        start: f64,
        slot: InputSlot,
        description: &str,
    ) {
        self.push(
            Declaration {
                start: Some(Value::Real(start)),
                ..Declaration::new(name, vr, Causality::Input, ty, description)
            },
            Access::Input(slot),
        );
    }

    pub fn output(
        &mut self,
        name: &str,
        vr: VariableId,
        ty: ValueType,
        get: OutputGetter,
        deps: InitialDependencies,
        description: &str,
    ) {
        self.push(
            Declaration {
                initial_dependencies: deps,
                ..Declaration::new(name, vr, Causality::Output, ty, description)
            },
            Access::Output(get),
        );
    }

    pub fn real_parameter(
        &mut self,
        name: &str,
        vr: VariableId,
        ty: ValueType,
        get: fn(&Scene) -> f64,
        set: fn(&mut Scene, f64),
        description: &str,
    ) {
        self.push(
            Declaration {
                start: Some(Value::Real(get(self.scene))),
                ..Declaration::new(name, vr, Causality::Parameter, ty, description)
            },
            Access::RealParameter {
                get,
                set,
                applied: None,
            },
        );
    }

    pub fn integer_parameter(
        &mut self,
        name: &str,
        vr: VariableId,
        ty: ValueType,
        get: fn(&Scene) -> i32,
        set: fn(&mut Scene, i32) -> Result<(), String>,
        description: &str,
    ) {
        self.push(
            Declaration {
                start: Some(Value::Integer(get(self.scene))),
                ..Declaration::new(name, vr, Causality::Parameter, ty, description)
            },
            Access::IntegerParameter { get, set },
        );
    }

    /// A calculated parameter (`rod.frequency[k]`).
    pub fn calculated_parameter(
        &mut self,
        name: String,
        vr: VariableId,
        ty: ValueType,
        access: Access,
        deps: InitialDependencies,
        description: String,
    ) {
        self.push(
            Declaration {
                initial_dependencies: deps,
                ..Declaration::new(name, vr, Causality::CalculatedParameter, ty, description)
            },
            access,
        );
    }
}
