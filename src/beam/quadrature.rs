//! Gauss-Legendre quadrature on [0, 1].

/// 4-point Gauss-Legendre nodes and weights on [0, 1]: exact for polynomials of degree <= 7,
/// which covers every shape integral here (cubic x cubic x quadratic weight = degree 8 is
/// never needed: the highest product is cubic x cubic = 6, or slope^2 x s^2 = 6).
pub const GAUSS4: [(f64, f64); 4] = {
    // Abramowitz and Stegun 25.4.30, mapped from [-1, 1] to [0, 1].
    const A: f64 = 0.339_981_043_584_856_3;
    const B: f64 = 0.861_136_311_594_052_6;
    const WA: f64 = 0.652_145_154_862_546_1;
    const WB: f64 = 0.347_854_845_137_453_9;
    [
        ((1.0 - B) / 2.0, WB / 2.0),
        ((1.0 - A) / 2.0, WA / 2.0),
        ((1.0 + A) / 2.0, WA / 2.0),
        ((1.0 + B) / 2.0, WB / 2.0),
    ]
};

#[cfg(test)]
mod tests {
    use super::GAUSS4;

    #[test]
    fn integrates_degree_seven_exactly() {
        for k in 0..=7 {
            let q: f64 = GAUSS4.iter().map(|(x, w)| w * x.powi(k)).sum();
            let exact = 1.0 / (k as f64 + 1.0);
            assert!((q - exact).abs() < 1e-15, "degree {k}: {q} vs {exact}");
        }
    }
}
