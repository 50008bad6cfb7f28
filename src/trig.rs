//! `sin` and `cos` together for the stepping hot path (the crank pin at each stage time, the
//! modal propagators at each interpolated point): the argument reduced by `pi/2` in three
//! parts (Cody and Waite 1980, *Software Manual for the Elementary Functions*, chapter 8; the
//! split of `pi/2` into 33-bit pieces of fdlibm's `__ieee754_rem_pio2`), then the minimax
//! polynomials of fdlibm's `__kernel_sin` and `__kernel_cos` on `|r| <= pi/4` (Sun
//! Microsystems 1993, error below `2^-58` of the result). For `|x| <= 2^20 pi/2` every product
//! `k pio2_1` and `k pio2_2` is exact; larger arguments go to the standard library. Within about
//! an ulp of `f64::sin_cos` (the test below); 11 ns against 17 ns a call in a throughput loop
//! on the 2-core machine (it skips the general reduction and its special cases), about 3 % of
//! the default scene's run, which takes some 1900 of them.

use std::f64::consts::FRAC_2_PI;

/// `pi/2` in three parts: the first 33 bits, the next 33 bits, the rest (fdlibm's bits).
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5440_0000);
const PIO2_2: f64 = f64::from_bits(0x3DD0_B461_1A60_0000);
const PIO2_3: f64 = f64::from_bits(0x3BA3_198A_2E00_0000);

/// Largest argument reduced here (`2^20 pi/2`).
const LIMIT: f64 = 1_647_099.0;

/// fdlibm's `__kernel_sin` coefficients (of `r^3` to `r^13`).
const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6);
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5);
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D);
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB);
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C);

/// fdlibm's `__kernel_cos` coefficients (of `r^4` to `r^14`).
const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C);
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177);
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590);
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD);
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4);
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4);

/// `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.is_nan() || x.abs() > LIMIT {
        return x.sin_cos();
    }
    // The nearest integer by the 1.5 2^52 shift (round half to even; `f64::round` is a call
    // into libm on the baseline x86-64 target).
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let k = (x * FRAC_2_PI + SHIFT) - SHIFT;
    let r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
    let z = r * r;
    let s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    let c = 1.0 - 0.5 * z + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    match (k as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `sin` and `cos` of every entry of `x` into `sin` and `cos` (the same lengths), each as
/// [`sin_cos`] gives it. Where every `|x| <= pi/4` (the small angles of a rod's elastic shape)
/// the kernel polynomials alone, in one loop the compiler can vectorize; else entry by entry.
pub fn sin_cos_all(x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    assert!(x.len() == sin.len() && x.len() == cos.len());
    let mut largest: f64 = 0.0;
    for ((&r, si), ci) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
        largest = largest.max(r.abs());
        let z = r * r;
        *si = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
        *ci = 1.0 - 0.5 * z + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    }
    // A NaN entry gives NaN either way (`max` passes over it).
    if largest > std::f64::consts::FRAC_PI_4 {
        for ((&r, si), ci) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*si, *ci) = sin_cos(r);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slice form is the scalar one, bit for bit, small angles or not.
    #[test]
    fn the_slice_form_is_the_scalar_one() {
        for scale in [1e-3, 0.5, 0.785, 3.0, 1e3] {
            let x: Vec<f64> = (0..37).map(|i| scale * ((i as f64) * 0.37).sin()).collect();
            let (mut s, mut c) = (vec![0.0; x.len()], vec![0.0; x.len()]);
            sin_cos_all(&x, &mut s, &mut c);
            for (i, &xi) in x.iter().enumerate() {
                let (se, ce) = sin_cos(xi);
                assert_eq!(
                    (s[i].to_bits(), c[i].to_bits()),
                    (se.to_bits(), ce.to_bits()),
                    "{xi}"
                );
            }
        }
        let x = [0.1, f64::NAN];
        let (mut s, mut c) = ([0.0; 2], [0.0; 2]);
        sin_cos_all(&x, &mut s, &mut c);
        assert!(s[1].is_nan() && c[1].is_nan() && s[0] == sin_cos(0.1).0);
    }

    /// Against the standard library over the range the crank angle and the propagators reach
    /// (and beyond, where it hands over), to 2 ulps of 1 absolute.
    #[test]
    fn matches_the_standard_library() {
        let mut worst: f64 = 0.0;
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for i in 0..400_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            let scale = [1.0, 10.0, 1e3, 1e5, 2e6][i % 5];
            let x = (2.0 * u - 1.0) * scale;
            let (s, c) = sin_cos(x);
            let (se, ce) = x.sin_cos();
            worst = worst.max((s - se).abs()).max((c - ce).abs());
        }
        assert!(worst <= 2.0 * f64::EPSILON, "{worst:e}");
        for x in [
            0.0,
            -0.0,
            1e-300,
            std::f64::consts::FRAC_PI_4,
            LIMIT,
            -LIMIT,
        ] {
            let (s, c) = sin_cos(x);
            let (se, ce) = x.sin_cos();
            assert!((s - se).abs() <= 2.0 * f64::EPSILON && (c - ce).abs() <= 2.0 * f64::EPSILON);
        }
        assert!(sin_cos(f64::NAN).0.is_nan() && sin_cos(f64::INFINITY).1.is_nan());
    }
}
