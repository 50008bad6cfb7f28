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
}

impl DaeState {
    /// A state of `n` coordinates and `m` multipliers at `t = 0`, all zero (workspace sized
    /// once, so that later copies into it allocate nothing).
    pub fn zeros(n: usize, m: usize) -> DaeState {
        DaeState {
            q: vec![0.0; n],
            v: vec![0.0; n],
            qdd: vec![0.0; n],
            acc: vec![0.0; n],
            lambda: vec![0.0; m],
            ..Default::default()
        }
    }

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
    }
}

/// An accepted internal step that reaches past the communication point the state stands at
/// (dense output, [`super::Integrator::step_ahead`]): its start (time and the independent
/// coordinates, their rates and accelerations) and its end (the whole state). While `held`,
/// the mechanism's state at a communication point inside `[t0, end.t)` is the interpolant of
/// this step, and the next communication step continues from it rather than stepping again.
#[derive(Debug, Default)]
pub struct StepAhead {
    /// A step is held (else the other fields are workspace).
    pub held: bool,
    /// Start time of the held step, s.
    pub t0: f64,
    /// Independent coordinates `z`, rates `z'` and accelerations `z''` at `t0` (k each).
    pub z0: Vec<f64>,
    pub zd0: Vec<f64>,
    pub zdd0: Vec<f64>,
    /// The exponential integrator's remainder `z'' + w^2 z + c z'` at the step's middle (k;
    /// zero for the other integrators), for its interpolant.
    pub nmid: Vec<f64>,
    /// The state at the end of the held step, `end.t > t0`.
    pub end: DaeState,
}

impl StepAhead {
    /// Workspace for `k` independent coordinates of a state shaped like `like` (nothing held).
    pub fn sized(k: usize, like: &DaeState) -> StepAhead {
        StepAhead {
            held: false,
            t0: 0.0,
            z0: vec![0.0; k],
            zd0: vec![0.0; k],
            zdd0: vec![0.0; k],
            nmid: vec![0.0; k],
            end: like.clone(),
        }
    }
}

impl StepAhead {
    /// A copy of the step `source` holds or held (its buffers, whether or not `held` was
    /// cleared since), as a held step: the backup of a step about to be overwritten.
    pub fn save(&mut self, source: &StepAhead) {
        self.held = true;
        self.t0 = source.t0;
        self.z0.clone_from(&source.z0);
        self.zd0.clone_from(&source.zd0);
        self.zdd0.clone_from(&source.zdd0);
        self.nmid.clone_from(&source.nmid);
        self.end.clone_from(&source.end);
    }
}

impl Clone for StepAhead {
    fn clone(&self) -> Self {
        StepAhead {
            held: self.held,
            t0: self.t0,
            z0: self.z0.clone(),
            zd0: self.zd0.clone(),
            zdd0: self.zdd0.clone(),
            nmid: self.nmid.clone(),
            end: self.end.clone(),
        }
    }

    /// Reuses the buffers ([`StepAhead::save`] where a step is held); copies nothing but the
    /// flag when none is (the rest is then workspace).
    fn clone_from(&mut self, source: &Self) {
        if source.held {
            self.save(source);
        } else {
            self.held = false;
        }
    }
}

/// Equal when neither holds a step, or both hold the same one (the workspace of a state that
/// holds none does not count).
impl PartialEq for StepAhead {
    fn eq(&self, other: &Self) -> bool {
        self.held == other.held
            && (!self.held
                || (self.t0 == other.t0
                    && self.z0 == other.z0
                    && self.zd0 == other.zd0
                    && self.zdd0 == other.zdd0
                    && self.nmid == other.nmid
                    && self.end == other.end))
    }
}

/// Quintic Hermite interpolation on a step `[t0, t0 + h]` from `(z, z', z'')` at both ends, at
/// `s = (t - t0) / h` in [0, 1]: returns `(z(t), z'(t))` (the interpolant and its derivative).
/// Exact for polynomials of degree 5; error `O(h^6)` in `z` and `O(h^5)` in `z'` (the
/// Hermite basis of Hairer, Norsett and Wanner, *Solving ODEs I*, section II.6, for a second
/// order system whose accelerations are the right-hand side at the step's ends).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn hermite5(
    s: f64,
    h: f64,
    z0: f64,
    zd0: f64,
    zdd0: f64,
    z1: f64,
    zd1: f64,
    zdd1: f64,
) -> (f64, f64) {
    let (s2, s3) = (s * s, s * s * s);
    let (s4, s5) = (s3 * s, s3 * s2);
    let h2 = h * h;
    let b0 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5;
    let b1 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5;
    let b2 = 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5);
    let b3 = 10.0 * s3 - 15.0 * s4 + 6.0 * s5;
    let b4 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5;
    let b5 = 0.5 * (s3 - 2.0 * s4 + s5);
    let d0 = -30.0 * s2 + 60.0 * s3 - 30.0 * s4;
    let d1 = 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4;
    let d2 = 0.5 * (2.0 * s - 9.0 * s2 + 12.0 * s3 - 5.0 * s4);
    let d4 = -12.0 * s2 + 28.0 * s3 - 15.0 * s4;
    let d5 = 0.5 * (3.0 * s2 - 8.0 * s3 + 5.0 * s4);
    let z = b0 * z0 + b1 * h * zd0 + b2 * h2 * zdd0 + b3 * z1 + b4 * h * zd1 + b5 * h2 * zdd1;
    let zd = (d0 * (z0 - z1)) / h + d1 * zd0 + d2 * h * zdd0 + d4 * zd1 + d5 * h * zdd1;
    (z, zd)
}

#[cfg(test)]
mod tests {
    use super::hermite5;

    /// Exact for a quintic; the ends reproduced.
    #[test]
    fn hermite5_is_exact_for_quintics() {
        let f = |t: f64| {
            0.3 - 1.2 * t + 0.7 * t * t + 2.0 * t.powi(3) - 1.5 * t.powi(4) + 0.9 * t.powi(5)
        };
        let fd = |t: f64| -1.2 + 1.4 * t + 6.0 * t * t - 6.0 * t.powi(3) + 4.5 * t.powi(4);
        let fdd = |t: f64| 1.4 + 12.0 * t - 18.0 * t * t + 18.0 * t.powi(3);
        let (t0, h) = (0.4, 0.7);
        let t1 = t0 + h;
        for s in [0.0, 0.1, 0.37, 0.5, 0.93, 1.0] {
            let (z, zd) = hermite5(s, h, f(t0), fd(t0), fdd(t0), f(t1), fd(t1), fdd(t1));
            let t = t0 + s * h;
            assert!((z - f(t)).abs() < 1e-13, "{s}: {z} vs {}", f(t));
            assert!((zd - fd(t)).abs() < 1e-12, "{s}: {zd} vs {}", fd(t));
        }
    }
}
