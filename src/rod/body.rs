//! What the slider-crank needs from a flexible rod model (FFR or finite segments).
//!
//! The rod has its own generalized coordinates `q_r` (n of them). Frames: everything here is
//! in the global frame unless a name says otherwise. Three material points matter: the B end,
//! the C end and the material midpoint.

use faer::MatMut;
use nalgebra::Vector2;

/// A material point of the rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RodPoint {
    /// The end pinned to the crank.
    B,
    /// The end pinned to the slider.
    C,
    /// The material midpoint (arc length L/2).
    Mid,
}

/// Interface of a planar flexible rod body.
pub trait RodBody: Send {
    /// Number of generalized coordinates of the rod.
    fn n_coordinates(&self) -> usize;
    /// Typical magnitude of coordinate `i` (for convergence tests), in its own unit.
    fn coordinate_scale(&self, i: usize) -> f64;
    /// Undeformed rod with its B end at `b` and C end at `c` (|c - b| = L), moving rigidly with
    /// B velocity `vb` and angular velocity `omega` (rad/s). Writes `q` and `v` (n each).
    fn place_undeformed(
        &self,
        b: Vector2<f64>,
        c: Vector2<f64>,
        vb: Vector2<f64>,
        omega: f64,
        q: &mut [f64],
        v: &mut [f64],
    );
    /// The coordinates that carry the elastic deformation alone (modal coordinates of the FFR
    /// rod), if the model has such a split; the quasi-static start needs it.
    fn elastic_coordinates(&self) -> Option<std::ops::Range<usize>> {
        None
    }
    /// Circular frequencies (rad/s) of the elastic coordinates, in their order, where the
    /// model has them (the retained modes of the FFR rod).
    fn elastic_circular_frequencies(&self) -> Option<Vec<f64>> {
        None
    }
    /// The elastic coordinates as oscillators of unit modal mass, `(w^2, c)` each (1/s^2, 1/s),
    /// where the model's elastic coordinates are modes that leave the pins in place (the pinned
    /// modes of the chain on its modes): the exponential integrator (ETDRK4) takes them exactly.
    /// The FFR rod gives its own through [`RodBody::ffr_kernel`]; `None` elsewhere.
    fn modal_oscillators(&self) -> Option<Vec<(f64, f64)>> {
        None
    }
    /// Indices among the elastic coordinates of the retained axial modes (the FFR rod's; none
    /// elsewhere): the exponential integrator (ETDRK4) caps its phase on them.
    fn axial_mode_indices(&self) -> Vec<usize> {
        Vec::new()
    }
    /// Indices of the body frame's origin `R` (x, y) and angle `phi` among the coordinates,
    /// where the model has one frame carrying the chord: a point is then `R + s(q_elastic) +
    /// A(phi) u(q_elastic)`, with a share `s` common to every point (the FFR rod: none; the chain
    /// on its modes: its shear modes' move of the first segment's start).
    fn frame_coordinates(&self) -> Option<[usize; 3]> {
        None
    }
    /// The mechanism evaluates its equations on the independent coordinates in closed form on
    /// the frame (`mechanism::frame_coordinates_closed_form`: frame coordinates at 0, 1, 2, the elastic ones after
    /// them) instead of the general partitioned evaluation.
    fn frame_form(&self) -> bool {
        false
    }
    /// The FFR rod's shape integrals in fixed-size arrays, where the model is an FFR rod with
    /// 1 to [`crate::rod::ffr::MAX_MODES`] modes: the mechanism then evaluates its equations
    /// of motion on minimal coordinates in closed form (`mechanism::minimal`).
    fn ffr_kernel(&self) -> Option<&crate::rod::ffr::FfrKernel> {
        None
    }
    /// Mass matrix (n x n) into `m`.
    fn mass(&self, q: &[f64], m: MatMut<'_, f64>);
    /// Generalized forces: quadratic velocity terms, elastic and damping forces, and the
    /// velocity part of the axial-force (geometric) stiffening.
    fn forces(&self, q: &[f64], v: &[f64], f: &mut [f64]);
    /// The number of coordinates an evaluation of this model costs like, for the work budget of
    /// a communication step (`mechanism::stepping::WORK_BUDGET`): its own, unless its functions
    /// work on more (the chain on its modes through the chain's own functions).
    fn work_coordinates(&self) -> usize {
        self.n_coordinates()
    }
    /// Work units one evaluation costs beyond the dense terms of its
    /// [`Self::work_coordinates`] ([`crate::rod::cost`]): the FFR rod's axial coupling.
    fn extra_evaluation_cost(&self) -> f64 {
        0.0
    }
    /// [`Self::mass`] and [`Self::forces`] at the same coordinates, in one pass where the model
    /// can (the chain on its modes).
    fn mass_and_forces(&self, q: &[f64], v: &[f64], m: MatMut<'_, f64>, f: &mut [f64]) {
        self.mass(q, m);
        self.forces(q, v, f);
    }
    /// Add the generalized gravity forces `int dm g . dr/dq` (rod and end bodies) into `f`
    /// (n entries); `g` global, m/s^2.
    fn add_gravity(&self, q: &[f64], g: Vector2<f64>, f: &mut [f64]);
    /// Section forces by force summation ([`crate::rod::sections`]) at positions `q`,
    /// velocities `v` and accelerations `qdd`, with `force_c` the force on the rod at C and `g`
    /// gravity (global).
    fn section_loads(
        &self,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> crate::rod::SectionLoads;
    /// Add `c_k K_t + c_d C_t` (approximate `-dQ/dq`, `-dQ/dq'`) into `out` (n x n).
    fn add_tangent(&self, q: &[f64], v: &[f64], c_k: f64, c_d: f64, out: MatMut<'_, f64>);
    /// Global position of a material point.
    fn point(&self, p: RodPoint, q: &[f64]) -> Vector2<f64>;
    /// Global position of the material point at undeformed arc length `s` from B (clamped to
    /// `0..=L`), without allocating; the FMI 3.0 `rod.shape` output samples it.
    fn point_at(&self, s: f64, q: &[f64]) -> Vector2<f64>;
    /// The global positions of B, C and the midpoint together (one evaluation of the frame's
    /// rotation where the model has one).
    fn points(&self, q: &[f64]) -> [Vector2<f64>; 3] {
        [
            self.point(RodPoint::B, q),
            self.point(RodPoint::C, q),
            self.point(RodPoint::Mid, q),
        ]
    }

    /// The midpoint deflection `v_mid` (m): the transverse distance of the material midpoint
    /// from the chord B -> C, positive to the left of B -> C (docs/physics.md, "Output
    /// definitions"); from [`RodBody::points`] unless the model has it cheaper (a floating
    /// frame: in the body frame, where the distance is the same and no rotation is needed).
    fn mid_deflection(&self, q: &[f64]) -> f64 {
        chord_distance(self.points(q))
    }
    /// The midpoint deflection output, m, with the accelerations `qdd` and gravity: the
    /// positions' [`RodBody::mid_deflection`], plus the quasi-static response of modes left out
    /// of the dynamics where the model keeps their residual flexibility (the FFR rod with a mode
    /// band).
    fn mid_deflection_dynamic(&self, q: &[f64], _qdd: &[f64], _gravity: Vector2<f64>) -> f64 {
        self.mid_deflection(q)
    }
    /// Jacobian `d r_p / d q` (2 x n) into `out`.
    fn point_jacobian(&self, p: RodPoint, q: &[f64], out: MatMut<'_, f64>);
    /// `(d/dt J_p) q'`: the velocity-product part of the point's acceleration.
    fn point_bias_acceleration(&self, p: RodPoint, q: &[f64], v: &[f64]) -> Vector2<f64>;
    /// Add `c d(J_p^T f)/dq` (n x n) into `out`, for a constant global force `f` at point p.
    fn add_point_force_tangent(
        &self,
        p: RodPoint,
        q: &[f64],
        f: Vector2<f64>,
        c: f64,
        out: MatMut<'_, f64>,
    );
    /// Kinetic energy, J.
    fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64;
    /// Strain energy (elastic potential), J.
    fn strain_energy(&self, q: &[f64]) -> f64;
    /// Linear momentum of the rod, kg m/s.
    fn linear_momentum(&self, q: &[f64], v: &[f64]) -> Vector2<f64>;
    /// Natural frequencies under the rod's reference or end conditions, Hz, ascending.
    fn frequencies_hz(&self) -> &[f64];
    /// The lowest bending frequency among [`RodBody::frequencies_hz`], Hz, where the rod tells
    /// bending from axial modes (the FFR rod); `None` otherwise.
    fn first_bending_hz(&self) -> Option<f64> {
        None
    }
    /// What the rod keeps, in words (the FFR rod: its retained modes and their kinds).
    fn describe(&self) -> String {
        format!("{} natural frequencies", self.frequencies_hz().len())
    }
    /// Rod length L, m.
    fn length(&self) -> f64;
    /// Mass of the rod with its end bodies (big end at B, small end at C), kg.
    fn total_mass(&self) -> f64;
    /// The highest natural frequency the model carries, Hz (the explicit integrator's step
    /// limit follows from it). By default the highest of `frequencies_hz`.
    fn highest_frequency_hz(&self) -> f64 {
        self.frequencies_hz().iter().cloned().fold(0.0, f64::max)
    }
}

/// The signed distance of `points[2]` from the line `points[0] -> points[1]`, positive to its
/// left (0 for coincident ends).
pub fn chord_distance(points: [Vector2<f64>; 3]) -> f64 {
    let [b, c, mid] = points;
    let chord = c - b;
    let length = chord.norm();
    if length == 0.0 {
        return 0.0;
    }
    let d = mid - b;
    (chord.x * d.y - chord.y * d.x) / length
}
