//! The matrix of settings the report runs on every case, and the reference setting.

use flexrod::scene::ReferenceKind;

use super::Setting;

/// The reference setting of every case: the most complete model at its finest setting.
pub fn reference_setting(quick: bool) -> Setting {
    if quick {
        Setting::seg(32, 5e-5)
    } else {
        Setting::seg(64, 1e-5)
    }
}

/// The settings run on every case (the reference among them); `quick`: a reduced matrix.
pub fn matrix(quick: bool) -> Vec<Setting> {
    use ReferenceKind::*;
    let mut v = Vec::new();
    if quick {
        v.push(Setting::ffr(false, 8, 4, 1e-4));
        v.push(Setting::ffr(true, 8, 3, 3e-4));
        v.push(Setting::ffr(true, 8, 4, 1e-4));
        v.push(Setting::seg(16, 1e-4));
        v.push(Setting::rk4(8, 3, 3e-4));
        v.push(Setting::auto(8, 3, 1e-3));
        v.push(Setting::dopri5(8, 3, 1e-3));
        v.push(Setting::seg_auto(16, 1e-3));
        v.push(Setting::modal_auto(32, 3, 1e-3));
        v.push(reference_setting(true));
        return v;
    }
    // FFR with axial stiffening: modes and step on 8 elements, then mesh, reference
    // conditions, numerical damping.
    for modes in [2, 3, 4, 6] {
        for h in [2e-5, 5e-5, 1e-4, 2e-4, 3e-4, 5e-4] {
            v.push(Setting::ffr(true, 8, modes, h));
        }
    }
    for (el, modes) in [(4, 3), (4, 4), (16, 4), (16, 8)] {
        for h in [5e-5, 1e-4, 3e-4] {
            v.push(Setting::ffr(true, el, modes, h));
        }
    }
    v.push(Setting::ffr(true, 16, 8, 1e-5));
    for r in [MeanAxis, BodyFixedMid] {
        v.push(Setting::ffr(true, 8, 4, 1e-4).with_reference(r));
        v.push(Setting::ffr(true, 8, 4, 3e-4).with_reference(r));
    }
    for rho in [0.0, 0.5, 1.0] {
        v.push(Setting::ffr(true, 8, 3, 3e-4).rho(rho));
        v.push(Setting::ffr(true, 8, 4, 1e-4).rho(rho));
    }
    // The explicit path: RK4 with projection, up to its stability limit (w_max h < 2.78).
    for (modes, steps) in [
        (2, &[2e-4, 3e-4, 4e-4, 5e-4, 6e-4, 7e-4][..]),
        (3, &[1e-4, 2e-4, 2.5e-4, 3e-4, 3.5e-4][..]),
        (4, &[5e-5, 1e-4, 1.5e-4][..]),
    ] {
        for &h in steps {
            v.push(Setting::rk4(8, modes, h));
        }
    }
    v.push(Setting::rk4(4, 3, 3e-4));
    // The error-controlled path (`auto`): the cost of each tolerance.
    for (modes, tolerances) in [(3, &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4][..]), (4, &[1e-3][..])] {
        for &tol in tolerances {
            v.push(Setting::auto(8, modes, tol));
        }
    }
    // The Dormand-Prince pair on the same closed-form minimal coordinates (for comparison with
    // the RK4(3) pair `auto` takes).
    for tol in [1e-2, 3e-3, 1e-3, 3e-4] {
        v.push(Setting::dopri5(8, 3, tol));
    }
    for n in [16, 32] {
        for tol in [1e-2, 1e-3] {
            v.push(Setting::seg_auto(n, tol));
        }
    }
    // The chain on its modes: segments and tolerance.
    for n in [16, 32, 64] {
        for tol in [1e-3, 1e-4] {
            v.push(Setting::modal_auto(n, 3, tol));
        }
    }
    // Linear FFR modes (1985).
    for (el, modes) in [(8, 3), (8, 4)] {
        for h in [1e-4, 3e-4] {
            v.push(Setting::ffr(false, el, modes, h));
        }
    }
    v.push(Setting::ffr(false, 16, 8, 1e-5));
    // Finite segments.
    for n in [4, 8, 16, 32] {
        for h in [2e-5, 5e-5, 1e-4, 2e-4, 3e-4] {
            v.push(Setting::seg(n, h));
        }
    }
    v.push(Setting::seg(16, 1e-4).rho(0.5));
    v.push(Setting::seg(16, 1e-4).rho(1.0));
    // The reference's own convergence, and the reference.
    v.push(Setting::seg(32, 1e-5));
    v.push(Setting::seg(64, 2e-5));
    v.push(reference_setting(false));
    v
}
