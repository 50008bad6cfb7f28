//! Typed errors of the model. Every message names the offending value and its allowed range.

use std::fmt;

/// Everything that can go wrong while building or running a model.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// A parameter outside its allowed range.
    InvalidParameter {
        name: &'static str,
        value: f64,
        allowed: String,
    },
    /// An integer parameter (a count, an index) outside its allowed range.
    InvalidInteger {
        name: &'static str,
        value: i64,
        allowed: String,
    },
    /// Reference conditions that leave a rigid-body mode in or over-constrain the rod.
    ReferenceConditions { message: String },
    /// More modes requested than the reduced rod has.
    TooManyModes { requested: usize, available: usize },
    /// The eigenproblem or a factorization failed (mass matrix not positive definite, ...).
    Numerical { message: String },
    /// A scene file that does not parse or names an unknown key.
    Scene { origin: String, message: String },
    /// The integrator could not complete a step; the state before the step is kept.
    StepFailed {
        time: f64,
        step: f64,
        reason: String,
    },
    /// A communication step that would need more internal steps than allowed
    /// (`mechanism::MAX_INTERNAL_STEPS`); nothing changed.
    TooMuchWork {
        time: f64,
        step: f64,
        message: String,
    },
    /// A model whose build or evaluation is predicted to cost more than the limits of one call
    /// (`rod::cost`); refused before the work starts.
    TooCostly { message: String },
    /// A step whose rod deflection exceeds `rod.deflection_limit` under the policy "discard"
    /// or "error"; the state before the step is kept.
    DeflectionLimit {
        time: f64,
        deflection: f64,
        limit: f64,
        /// Policy "discard" (the step refused, to be retried); false: "error".
        discard: bool,
        /// What the limit stands for in this rod model, and what goes further (words).
        range: &'static str,
    },
    /// A text of the scene (`name`, `description`) with a character modelDescription.xml
    /// cannot carry.
    InvalidText {
        key: &'static str,
        character: char,
        /// Position of the character, in characters from 1.
        position: usize,
        length: usize,
    },
    /// A call that the model cannot serve in its current state (e.g. bad state bytes).
    State { message: String },
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::InvalidParameter {
                name,
                value,
                allowed,
            } => write!(
                f,
                "parameter {name} = {} is out of range: allowed {allowed}",
                crate::text::number(*value)
            ),
            ModelError::InvalidInteger {
                name,
                value,
                allowed,
            } => write!(f, "parameter {name} = {value} is out of range: allowed {allowed}"),
            ModelError::ReferenceConditions { message } => {
                write!(f, "reference conditions rejected: {message}")
            }
            ModelError::TooManyModes {
                requested,
                available,
            } => write!(
                f,
                "rod.modes = {requested} is out of range: allowed 0..={available} (the number of elastic coordinates left by the reference conditions)"
            ),
            ModelError::Numerical { message } => write!(f, "numerical failure: {message}"),
            ModelError::TooCostly { message } => write!(f, "model refused by its cost: {message}"),
            ModelError::Scene { origin, message } => write!(f, "scene {origin}: {message}"),
            ModelError::StepFailed { time, step, reason } => write!(
                f,
                "step from t = {} s with h = {step:e} s failed: {reason}; the state before the step is kept",
                crate::text::time(*time)
            ),
            ModelError::TooMuchWork {
                time,
                step,
                message,
            } => write!(
                f,
                "communication step from t = {} s with h = {step:e} s refused: {message}; the state before the step is kept, take smaller communication steps",
                crate::text::time(*time)
            ),
            ModelError::DeflectionLimit {
                time,
                deflection,
                limit,
                discard,
                range,
            } => write!(
                f,
                "the step to t = {} s reaches rod deflection |v_mid/L| = {deflection:.4e}, beyond rod.deflection_limit = {limit} ({range}; rod.deflection_policy = {}): the step is refused and the state before it kept",
                crate::text::time(*time),
                if *discard { "discard" } else { "error" }
            ),
            ModelError::InvalidText {
                key,
                character,
                position,
                length,
            } => write!(
                f,
                "{key} holds the character U+{:04X} at position {position} (of {length} characters): allowed only characters an XML 1.0 attribute carries unchanged (no control character U+0000 to U+001F, no U+FFFE, U+FFFF)",
                *character as u32
            ),
            ModelError::State { message } => write!(f, "{message}"),
        }
    }
}

impl std::error::Error for ModelError {}

/// Check that `value` is finite and inside the closed physical window `[low, high]` (in the
/// parameter's SI unit `unit`): past it, the model's numbers mean nothing (a
/// denormal density would give natural frequencies of 1e149 Hz).
pub fn require_within(
    name: &'static str,
    value: f64,
    low: f64,
    high: f64,
    unit: &str,
) -> Result<(), ModelError> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name,
            value,
            allowed: format!("a finite value in [{low:e}, {high:e}] {unit}"),
        })
    }
}

/// Check that `value` is finite and strictly positive.
pub fn require_positive(name: &'static str, value: f64) -> Result<(), ModelError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name,
            value,
            allowed: "a finite value > 0".into(),
        })
    }
}

/// Check that `value` is finite and >= 0.
pub fn require_non_negative(name: &'static str, value: f64) -> Result<(), ModelError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name,
            value,
            allowed: "a finite value >= 0".into(),
        })
    }
}
