//! Section forces of the rod (docs/real-rods.md, "Section forces and stress"): the axial
//! force, bending moment and the outer-fibre stress `abs(N/A) + abs(M) c / I` at cuts along
//! the rod, recovered by **force summation**: the section force at a cut is the resultant of
//! everything acting on the part of the rod beyond it (towards C): the pin force at C, the
//! small end's gravity and d'Alembert force and couple, and `dm (g - a)` of the rod's mass
//! beyond the cut, with the accelerations of the model's own kinematics. Unlike the curvature
//! of truncated modes, this is exact in statics whatever the number of modes (beam theory's
//! `q L^2 / 8` to round-off) and it is what both rod models can give alike.
//!
//! Signs: `N` positive in tension; `M` positive when it bends the rod towards `+v` (to the
//! left of B->C), i.e. `M = E I v''` of the beam: `M = sum (r' - r_cut) x F'` over the part
//! beyond the cut (global z component).

use nalgebra::Vector2;

use crate::beam::SectionTable;

/// The section forces the outputs report, at one time.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SectionLoads {
    /// Axial force at the material midpoint, N, tension positive.
    pub axial_force_mid: f64,
    /// Bending moment at the midpoint, N m, positive when it bends the rod towards +v.
    pub bending_moment_mid: f64,
    /// Largest `abs(N/A) + abs(M) c / I` over the cuts, Pa (NaN without fibre distances).
    pub stress_max: f64,
    /// Where it occurs, m from B.
    pub stress_max_position: f64,
}

/// A cut through the rod: its position and the section on both sides (a step in the table
/// has two).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutSection {
    /// Arc length from B, m.
    pub s: f64,
    /// `(1 / A, c / I)` just before and at `s` (1/m^2, 1/m^3; `c / I` NaN without a fibre
    /// distance).
    sides: [(f64, f64); 2],
}

impl CutSection {
    pub fn new(table: &SectionTable, s: f64) -> CutSection {
        let side = |x: f64| {
            let v = table.at(x);
            (
                1.0 / v.area,
                v.fibre_distance.map_or(f64::NAN, |c| c / v.area_moment),
            )
        };
        let eps = 1e-9 * table.length();
        CutSection {
            s,
            sides: [side((s - eps).max(0.0)), side(s)],
        }
    }

    /// Largest outer-fibre stress of the two sides, Pa (a side without a fibre distance gives
    /// NaN, which `max` passes over: -inf where neither side has one).
    pub fn stress(&self, n: f64, m: f64) -> f64 {
        let [(a0, k0), (a1, k1)] = self.sides;
        f64::NEG_INFINITY
            .max(n.abs() * a0 + m.abs() * k0)
            .max(n.abs() * a1 + m.abs() * k1)
    }
}

/// `a x b` (z component).
#[inline]
pub(crate) fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The resultant of the loads beyond the current cut, walked from C towards B.
pub(crate) struct LoadWalk {
    /// Resultant force, N.
    pub force: Vector2<f64>,
    /// Resultant moment about the global origin, N m.
    pub moment: f64,
    pub out: SectionLoads,
}

impl LoadWalk {
    pub fn new() -> LoadWalk {
        LoadWalk {
            force: Vector2::zeros(),
            moment: 0.0,
            out: SectionLoads {
                stress_max: f64::NEG_INFINITY,
                ..Default::default()
            },
        }
    }

    /// Add a force `f` at `r` and a couple `couple`.
    #[inline]
    pub fn add(&mut self, r: Vector2<f64>, f: Vector2<f64>, couple: f64) {
        self.force += f;
        self.moment += cross(r, f) + couple;
    }

    /// The cut `cut` at `r` with the rod's axis `t` (unit) there; `mid`: it is the midpoint.
    pub fn cut(&mut self, cut: &CutSection, r: Vector2<f64>, t: Vector2<f64>, mid: bool) {
        let n = self.force.dot(&t);
        let m = self.moment - cross(r, self.force);
        if mid {
            self.out.axial_force_mid = n;
            self.out.bending_moment_mid = m;
        }
        let stress = cut.stress(n, m);
        if stress > self.out.stress_max || (stress.is_nan() && !self.out.stress_max.is_nan()) {
            self.out.stress_max = stress;
            self.out.stress_max_position = cut.s;
        }
    }
}
