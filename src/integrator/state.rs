//! The integrator's state of a constrained mechanical system.

/// Positions, velocities, accelerations, the acceleration-like variable `a`, and multipliers.
#[derive(Debug, PartialEq, Default)]
pub struct DaeState {
    pub t: f64,
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    /// q'' (true accelerations).
    pub qdd: Vec<f64>,
    /// The algorithmic acceleration `a`.
    pub acc: Vec<f64>,
    pub lambda: Vec<f64>,
    /// The step an adaptive integrator proposes next, s (0: none yet).
    pub step_hint: f64,
    /// The amplitude of the motion the error control's accuracy refers to (the mechanism keeps
    /// the largest `|v_mid / L|` so far here; 0 at the start).
    pub amplitude: f64,
}

impl DaeState {
    /// Accept a completed step: the state at `t` becomes `(q, v, qdd, acc, lambda)` (no
    /// allocation; the sizes match).
    pub fn accept(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        acc: &[f64],
        lambda: &[f64],
    ) {
        self.t = t;
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.qdd.copy_from_slice(qdd);
        self.acc.copy_from_slice(acc);
        self.lambda.copy_from_slice(lambda);
    }
}

impl Clone for DaeState {
    fn clone(&self) -> Self {
        DaeState {
            t: self.t,
            q: self.q.clone(),
            v: self.v.clone(),
            qdd: self.qdd.clone(),
            acc: self.acc.clone(),
            lambda: self.lambda.clone(),
            step_hint: self.step_hint,
            amplitude: self.amplitude,
        }
    }

    /// Reuses the buffers: no allocation when the sizes match (the backup before each step).
    fn clone_from(&mut self, source: &Self) {
        self.t = source.t;
        self.q.clone_from(&source.q);
        self.v.clone_from(&source.v);
        self.qdd.clone_from(&source.qdd);
        self.acc.clone_from(&source.acc);
        self.lambda.clone_from(&source.lambda);
        self.step_hint = source.step_hint;
        self.amplitude = source.amplitude;
    }
}
