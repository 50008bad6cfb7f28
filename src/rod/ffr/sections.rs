//! Section forces of the FFR rod by force summation ([`crate::rod::sections`]): mass samples
//! (3-point Gauss on every interval between cuts, exact for the mass and its first moment of
//! a linear section) and cuts at the nodes, element midpoints, stations and the midpoint, each
//! with its modal shape rows `S_hat(s)` precomputed. A shear-deformable rod's samples also carry
//! their rotary inertia `rho I ds`, whose couple `-rho I ds phi''` enters the moment (the frame's
//! angular acceleration; at 6000 rpm it is about 3 % of the automotive rod's midpoint moment,
//! tests/automotive_reference.rs).
//!
//! The sum runs in the body frame, with the samples beyond each cut summed once at
//! initialization into their mass moments ([`Sampling`]): sample `k` at `u_k = (x_k, 0) + S_k p`
//! (`x_k = x_B + s_k`) carries, in the body frame,
//! `f_k = dm_k (G - phi'' I~ u_k + phi'^2 u_k - S_k p'' - 2 phi' I~ S_k p')` with
//! `G = A^T (g - R'')` (the acceleration of Agrawal and Shabana 1985, eq. 3.9, with
//! `ubar' = S p'`), so the samples beyond a cut add the force
//! `m0 G - phi'' I~ U + phi'^2 U - A_S p'' - 2 phi' I~ A_S p'` with `U = (m_x, 0) + A_S p`, and
//! the moment about the frame's origin
//! `U x G - phi'' (m_xx + 2 B_x p + p^T C p) - (B_y p'' + p^T D p'') -
//! 2 phi' (B_x p' + p^T C p') - J phi''` with `m0 = sum dm`, `m_x = sum dm x`,
//! `m_xx = sum dm x^2`, `A_S = sum dm S`, `B = sum dm x S` (rows x, y),
//! `C = sum dm (S_x^T S_x + S_y^T S_y)`,
//! `D = sum dm (S_x^T S_y - S_y^T S_x)` and `J = sum rho I ds`: a few products per cut with
//! features built once per evaluation, instead of a pass over every sample. Equal to the
//! sample-by-sample sum to 1e-12 (the test below).

use std::cell::RefCell;

use nalgebra::Vector2;

use super::points::{rot, tilde};
use super::rod::FfrRod;
use crate::modal::ComponentModes;
use crate::rod::body::RodPoint;
use crate::rod::sections::{cross, CutSection, LoadWalk, SectionLoads};

/// The mass moments of the samples beyond each cut (towards C), one row of
/// `Sampling::width_for(n)` numbers per cut: `m0, m_x, m_xx, J`, then `A_S` (rows x, y), `B` (rows x, y), `C` and `D`
/// (row-major `n x n`), as in the module docs.
#[derive(Clone, Debug, Default)]
pub struct Sampling {
    beyond: Vec<f64>,
    n: usize,
    /// The features of an evaluation (`alpha`, `beta` and the moment's row, `6 n + 2 n^2`),
    /// allocated here once: the evaluation writes them in place.
    features: RefCell<Vec<f64>>,
    pub(super) cuts: Vec<CutSection>,
    pub(super) cut_shapes: Vec<f64>,
    pub(super) mid: usize,
}

/// One mass sample: arc length from B (m), mass (kg), rotary inertia (kg m^2) and its `S_hat`
/// rows (`2 n`: row x, then row y).
#[derive(Clone, Debug)]
pub(super) struct Sample {
    pub(super) s: f64,
    pub(super) dm: f64,
    pub(super) dj: f64,
    pub(super) rows: Vec<f64>,
}

fn shape_rows(modes: &ComponentModes, s: f64, out: &mut Vec<f64>) {
    let mesh = &modes.mesh;
    let (e, xi) = mesh.locate(s);
    let sm = mesh.shape(e, xi);
    let es = modes.element_shapes(e);
    let prod = sm * es;
    for r in 0..2 {
        for j in 0..modes.n_modes() {
            out.push(prod[(r, j)]);
        }
    }
}

/// The cut positions (ascending: nodes, element midpoints, the midpoint, the stations) and the
/// samples of every interval between them, `samples[i]` between `points[i]` and
/// `points[i + 1]`.
pub(super) fn samples(modes: &ComponentModes) -> (Vec<f64>, Vec<Vec<Sample>>) {
    let mesh = &modes.mesh;
    let def = &mesh.definition;
    let table = def.section_table();
    let length = def.properties.length;
    let rho = def.properties.density;
    let rotary = if def.shear_modulus.is_some() {
        rho
    } else {
        0.0
    };
    let ne = mesh.n_elements;
    let le = length / ne as f64;
    let mut points: Vec<f64> = (0..=ne).map(|i| i as f64 * le).collect();
    points.extend((0..ne).map(|i| (i as f64 + 0.5) * le));
    points.push(0.5 * length);
    points.extend(table.stations().iter().map(|st| st.position));
    points.sort_by(|a, b| a.total_cmp(b));
    points.dedup_by(|a, b| (*a - *b).abs() < 1e-12 * length);
    let gauss = [
        (-(0.6f64.sqrt()), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        (0.6f64.sqrt(), 5.0 / 9.0),
    ];
    let intervals = points
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            gauss
                .iter()
                .map(|&(x, wt)| {
                    let s = 0.5 * (a + b) + 0.5 * (b - a) * x;
                    let section = table.at(s);
                    let mut rows = Vec::with_capacity(2 * modes.n_modes());
                    shape_rows(modes, s, &mut rows);
                    Sample {
                        s,
                        dm: rho * section.area * 0.5 * (b - a) * wt,
                        dj: rotary * section.area_moment * 0.5 * (b - a) * wt,
                        rows,
                    }
                })
                .collect()
        })
        .collect();
    (points, intervals)
}

impl Sampling {
    pub fn new(modes: &ComponentModes, x_b: f64) -> Sampling {
        let table = modes.mesh.definition.section_table();
        let length = modes.mesh.definition.properties.length;
        let n = modes.n_modes();
        let width = Sampling::width_for(n);
        let (points, intervals) = samples(modes);
        let mut sampling = Sampling {
            beyond: vec![0.0; points.len() * width],
            n,
            features: RefCell::new(vec![0.0; width - 4 + 2 * n]),
            ..Default::default()
        };
        // Sums from C towards B: the row of cut i holds the intervals i, i + 1, ...
        for i in (0..intervals.len()).rev() {
            let (here, next) = sampling.beyond.split_at_mut((i + 1) * width);
            let row = &mut here[i * width..];
            row.copy_from_slice(&next[..width]);
            for k in &intervals[i] {
                let x = x_b + k.s;
                let (sx, sy) = k.rows.split_at(n);
                row[0] += k.dm;
                row[1] += k.dm * x;
                row[2] += k.dm * x * x;
                row[3] += k.dj;
                let (a, rest) = row[4..].split_at_mut(2 * n);
                let (b, rest) = rest.split_at_mut(2 * n);
                let (c, d) = rest.split_at_mut(n * n);
                for i in 0..n {
                    a[i] += k.dm * sx[i];
                    a[n + i] += k.dm * sy[i];
                    b[i] += k.dm * x * sx[i];
                    b[n + i] += k.dm * x * sy[i];
                    for j in 0..n {
                        c[i * n + j] += k.dm * (sx[i] * sx[j] + sy[i] * sy[j]);
                        d[i * n + j] += k.dm * (sx[i] * sy[j] - sy[i] * sx[j]);
                    }
                }
            }
        }
        for (i, &s) in points.iter().enumerate() {
            if (s - 0.5 * length).abs() < 1e-12 * length {
                sampling.mid = i;
            }
            sampling.cuts.push(CutSection::new(&table, s));
            shape_rows(modes, s, &mut sampling.cut_shapes);
        }
        sampling
    }

    /// Numbers per cut for `n` modes: `4 + 4 n + 2 n^2`.
    fn width_for(n: usize) -> usize {
        4 + 4 * n + 2 * n * n
    }
}

/// `a . b` over equal lengths, in four partial sums (which the compiler can keep in vector
/// registers).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    let mut s = [0.0; 4];
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            s[k] += x[k] * y[k];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

impl FfrRod {
    /// Body-frame `S_hat x` from the `2 n` shape rows.
    #[cfg(test)]
    fn apply(&self, rows: &[f64], x: &[f64]) -> Vector2<f64> {
        let n = self.n;
        let mut u = Vector2::zeros();
        for j in 0..n {
            u.x += rows[j] * x[j];
            u.y += rows[n + j] * x[j];
        }
        u
    }

    /// The section forces at the state `(q, v, q'')` with the force `force_c` on the rod at C
    /// and gravity `g` (all global), in the body frame. The samples beyond a cut give, with
    /// `alpha = phi'^2 p - p''` and `beta = phi'' p + 2 phi' p'` (module docs, expanded):
    /// `F_x = m0 G_x + m_x phi'^2 + A_x alpha + A_y beta`,
    /// `F_y = m0 G_y - m_x phi'' - A_x beta + A_y alpha`,
    /// `M = m_x G_y - (m_xx + J) phi'' + A_x (G_y p) - A_y (G_x p) - B_x (beta + phi'' p) -
    /// B_y p'' - p^T C beta - p^T D p''`: products of the cut's row with features built once.
    /// The pin force and the small end at C are added to every cut.
    pub fn section_loads_ffr(
        &self,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> SectionLoads {
        let n = self.n;
        let sm = &self.sampling;
        debug_assert_eq!(sm.n, n);
        let (c, s) = rot(q[2]);
        let to_body = |x: Vector2<f64>| Vector2::new(c * x.x + s * x.y, -s * x.x + c * x.y);
        let (w, al) = (v[2], qdd[2]);
        let (p, pd, pdd) = (&q[3..3 + n], &v[3..3 + n], &qdd[3..3 + n]);
        let big_g = to_body(g - Vector2::new(qdd[0], qdd[1]));
        // The pin force and the small end at C, at the point with the chord's foreshortening
        // (the end body's acceleration leaves out its rates, as the samples' do).
        let end = self.modes.mesh.definition.small_end;
        let u_c = self.ubar(RodPoint::C, q);
        let f_pin = to_body(force_c);
        let mut force_c_end = f_pin;
        let mut moment_c_end = cross(u_c, f_pin);
        if end.mass > 0.0 || end.inertia > 0.0 {
            let ud = self.shape_times(RodPoint::C, pd);
            let udd = self.shape_times(RodPoint::C, pdd);
            let a = tilde(u_c) * al - u_c * (w * w) + udd + tilde(ud) * (2.0 * w);
            let f = (big_g - a) * end.mass;
            force_c_end += f;
            moment_c_end += cross(u_c, f) - end.inertia * al;
        }
        let x_b = self.integrals.x_b;
        let frame = Frame {
            big_g,
            w,
            al,
            force_c_end,
            moment_c_end,
            x_b,
        };
        // One instance per mode count up to 8 (the loops' lengths known at compile time),
        // the general one above.
        match n {
            1 => self.walk_cuts::<1>(&frame, p, pd, pdd),
            2 => self.walk_cuts::<2>(&frame, p, pd, pdd),
            3 => self.walk_cuts::<3>(&frame, p, pd, pdd),
            4 => self.walk_cuts::<4>(&frame, p, pd, pdd),
            5 => self.walk_cuts::<5>(&frame, p, pd, pdd),
            6 => self.walk_cuts::<6>(&frame, p, pd, pdd),
            7 => self.walk_cuts::<7>(&frame, p, pd, pdd),
            8 => self.walk_cuts::<8>(&frame, p, pd, pdd),
            _ => self.walk_cuts::<0>(&frame, p, pd, pdd),
        }
    }

    /// The walk over the cuts of [`FfrRod::section_loads_ffr`] for `N` modes (`N = 0`: the
    /// rod's own count, known only at run time).
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn walk_cuts<const N: usize>(
        &self,
        frame: &Frame,
        p: &[f64],
        pd: &[f64],
        pdd: &[f64],
    ) -> SectionLoads {
        let n = if N == 0 { self.n } else { N };
        let sm = &self.sampling;
        let Frame {
            big_g,
            w,
            al,
            force_c_end,
            moment_c_end,
            x_b,
        } = *frame;
        let (p, pd, pdd) = (&p[..n], &pd[..n], &pdd[..n]);
        // The features: alpha, beta (n each) and the moment's row from A_S on
        // (`4 n + 2 n^2`, the layout of a cut's row).
        let width = Sampling::width_for(n);
        let mut features = sm.features.borrow_mut();
        let (alpha, rest) = features.split_at_mut(n);
        let (beta, fm) = rest.split_at_mut(n);
        let fm = &mut fm[..width - 4];
        let (a0, b0, c0, d0) = (0, 2 * n, 4 * n, 4 * n + n * n);
        for i in 0..n {
            alpha[i] = w * w * p[i] - pdd[i];
            beta[i] = al * p[i] + 2.0 * w * pd[i];
            fm[a0 + i] = big_g.y * p[i];
            fm[a0 + n + i] = -big_g.x * p[i];
            fm[b0 + i] = -(beta[i] + al * p[i]);
            fm[b0 + n + i] = -pdd[i];
        }
        for i in 0..n {
            for j in 0..n {
                fm[c0 + i * n + j] = -p[i] * beta[j];
                fm[d0 + i * n + j] = -p[i] * pdd[j];
            }
        }
        let (alpha, beta, fm) = (&*alpha, &*beta, &*fm);
        let mut walk = LoadWalk::new();
        let axis = Vector2::new(1.0, 0.0);
        // From C towards B, as the sample-by-sample walk: the first of equal stresses nearest C.
        for i in (0..sm.cuts.len()).rev() {
            let row = &sm.beyond[i * width..(i + 1) * width];
            let (m0, mx, mxx, j) = (row[0], row[1], row[2], row[3]);
            let (ax, ay) = (&row[4..4 + n], &row[4 + n..4 + 2 * n]);
            let (ax_alpha, ay_beta) = (dot(ax, alpha), dot(ay, beta));
            let (ax_beta, ay_alpha) = (dot(ax, beta), dot(ay, alpha));
            let f = Vector2::new(
                m0 * big_g.x + mx * w * w + ax_alpha + ay_beta,
                m0 * big_g.y - mx * al - ax_beta + ay_alpha,
            );
            walk.force = force_c_end + f;
            walk.moment = moment_c_end + mx * big_g.y - (mxx + j) * al + dot(&row[4..], fm);
            let rows = &sm.cut_shapes[2 * n * i..2 * n * (i + 1)];
            let mut u = Vector2::new(x_b + sm.cuts[i].s, 0.0);
            for k in 0..n {
                u.x += rows[k] * p[k];
                u.y += rows[n + k] * p[k];
            }
            walk.cut(&sm.cuts[i], u, axis, i == sm.mid);
        }
        walk.out
    }
}

/// The frame's motion and the loads at C of one evaluation of [`FfrRod::section_loads_ffr`]
/// (body frame): `G = A^T (g - R'')`, `phi'`, `phi''`, the force and the moment (about the
/// frame's origin) of the pin force and the small end, and `x_B`.
struct Frame {
    big_g: Vector2<f64>,
    w: f64,
    al: f64,
    force_c_end: Vector2<f64>,
    moment_c_end: f64,
    x_b: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::{ModeSelection, ReferenceConditions};
    use crate::rod::spec::RodSpec;

    /// The automotive rod's section table, shear, a small end and the piston's mass in the
    /// modes (mass-loaded, so the modes move the pins too), `count` modes.
    fn rod(count: usize) -> FfrRod {
        let spec: RodSpec = toml::from_str(concat!(
            "model = \"ffr\"\nlength = 0.1507\nyoungs_modulus = 2.0e11\ndensity = 7800.0\n",
            "shear_deformation = true\nshear_modulus = 7.7e10\nelements = 8\nmodes = 5\n",
            "loaded_modes = true\n",
            "[[section]]\nposition = 0.0\narea = 2.43e-4\narea_moment = 2.852e-8\n",
            "fibre_distance = 0.015\n",
            "[[section]]\nposition = 0.07535\narea = 2.16e-4\narea_moment = 1.613e-8\n",
            "fibre_distance = 0.012\n",
            "[[section]]\nposition = 0.1507\narea = 1.89e-4\narea_moment = 7.623e-9\n",
            "fibre_distance = 0.009\n",
            "[big_end]\nmass = 0.22\ninertia = 3.1e-4\n[small_end]\nmass = 0.05\ninertia = 1.1e-5",
        ))
        .expect("a valid rod");
        let (_, added) = crate::rod::ffr_mode_choice(&spec, 0.55);
        let reference = ReferenceConditions::from_kind(spec.reference, spec.elements).unwrap();
        let modes = ComponentModes::from_definition_loaded(
            spec.definition().unwrap(),
            spec.elements,
            reference,
            spec.mass,
            &ModeSelection::Count(count),
            &added,
        )
        .unwrap();
        FfrRod::new(modes, 0.02, true)
    }

    /// The same sum sample by sample in the global frame: `dm (g - a)` at `r_k` with the
    /// acceleration `R'' + A (phi'' I~ u - phi'^2 u + S p'' + 2 phi' I~ S p')`.
    fn by_samples(
        rod: &FfrRod,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> SectionLoads {
        use super::super::points::rotate;
        let n = rod.n;
        let (c, s) = rot(q[2]);
        let (w, al) = (v[2], qdd[2]);
        let origin = Vector2::new(q[0], q[1]);
        let r_acc = Vector2::new(qdd[0], qdd[1]);
        let (p, pd, pdd) = (&q[3..3 + n], &v[3..3 + n], &qdd[3..3 + n]);
        let accel = |u: Vector2<f64>, ud: Vector2<f64>, udd: Vector2<f64>| {
            r_acc
                + rotate(
                    c,
                    s,
                    tilde(u) * al - u * (w * w) + udd + tilde(ud) * (2.0 * w),
                )
        };
        let mut walk = LoadWalk::new();
        let end = rod.modes.mesh.definition.small_end;
        let u_c = rod.ubar(RodPoint::C, q);
        let r_c = origin + rotate(c, s, u_c);
        walk.add(r_c, force_c, 0.0);
        let (ud, udd) = (
            rod.shape_times(RodPoint::C, pd),
            rod.shape_times(RodPoint::C, pdd),
        );
        walk.add(r_c, (g - accel(u_c, ud, udd)) * end.mass, -end.inertia * al);
        let (points, intervals) = samples(&rod.modes);
        let axis = rotate(c, s, Vector2::new(1.0, 0.0));
        let sm = &rod.sampling;
        for i in (0..points.len()).rev() {
            for k in intervals.get(i).into_iter().flatten().rev() {
                let u = Vector2::new(rod.integrals.x_b + k.s, 0.0) + rod.apply(&k.rows, p);
                let a = accel(u, rod.apply(&k.rows, pd), rod.apply(&k.rows, pdd));
                walk.add(origin + rotate(c, s, u), (g - a) * k.dm, -k.dj * al);
            }
            let rows = &sm.cut_shapes[2 * n * i..2 * n * (i + 1)];
            let u = Vector2::new(rod.integrals.x_b + points[i], 0.0) + rod.apply(rows, p);
            walk.cut(&sm.cuts[i], origin + rotate(c, s, u), axis, i == sm.mid);
        }
        walk.out
    }

    /// The mass moments give the sample-by-sample sum to 1e-12 over random states (deflections
    /// to 5 % of the length, 6000 rpm, large accelerations, gravity, a pin force), with 1, 3
    /// and 5 modes (the walks compiled for their counts) and 10 (the walk for any count).
    #[test]
    fn mass_moments_equal_the_sum_over_the_samples() {
        for count in [1, 3, 5, 10] {
            mass_moments_equal_the_sum_over_the_samples_with(count);
        }
    }

    fn mass_moments_equal_the_sum_over_the_samples_with(count: usize) {
        let rod = rod(count);
        let n = rod.n;
        assert_eq!(n, count);
        let mut seed = 7u64;
        let mut next = move |scale: f64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            scale * (((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0)
        };
        for _ in 0..20 {
            let mut q = vec![0.0; 3 + n];
            let mut v = vec![0.0; 3 + n];
            let mut a = vec![0.0; 3 + n];
            for i in 0..3 + n {
                let modal = i >= 3;
                q[i] = next(if modal { 2e-3 } else { 1.0 });
                v[i] = next(if modal { 10.0 } else { 700.0 });
                a[i] = next(if modal { 1e5 } else { 4e5 });
            }
            let g = Vector2::new(next(10.0), next(10.0));
            let f = Vector2::new(next(4e4), next(4e4));
            let fast = rod.section_loads_ffr(&q, &v, &a, g, f);
            let slow = by_samples(&rod, &q, &v, &a, g, f);
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs().max(1.0);
            assert!(
                close(fast.axial_force_mid, slow.axial_force_mid),
                "{fast:?} {slow:?}"
            );
            assert!(
                close(fast.bending_moment_mid, slow.bending_moment_mid),
                "{fast:?} {slow:?}"
            );
            assert!(close(fast.stress_max, slow.stress_max), "{fast:?} {slow:?}");
            assert_eq!(fast.stress_max_position, slow.stress_max_position);
        }
        // At rest without loads every stress is 0: the first cut from C is reported, as the
        // sample walk and the segment chain report it.
        let zero = vec![0.0; 3 + n];
        let none = Vector2::zeros();
        let fast = rod.section_loads_ffr(&zero, &zero, &zero, none, none);
        let slow = by_samples(&rod, &zero, &zero, &zero, none, none);
        assert_eq!(fast.stress_max_position, slow.stress_max_position);
        assert_eq!(fast.stress_max_position, rod.length);
    }
}
