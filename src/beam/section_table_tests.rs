//! Unit tests of the section table.
use super::*;

fn st(position: f64, area: f64, area_moment: f64) -> SectionStation {
    SectionStation {
        position,
        area,
        area_moment,
        shear_area: None,
        fibre_distance: None,
    }
}

#[test]
fn linear_between_stations_and_steps() {
    let t = SectionTable::new(
        1.0,
        &[
            st(0.0, 1.0, 2.0),
            st(0.5, 3.0, 2.0),
            st(0.5, 5.0, 1.0),
            st(1.0, 5.0, 1.0),
        ],
    )
    .unwrap();
    assert!((t.at(0.25).area - 2.0).abs() < 1e-15);
    assert_eq!(t.at(0.5).area, 5.0);
    assert!((t.at(0.25).shear_area - 2.0 / 1.2).abs() < 1e-15);
    let (a, m) = t.tail_integrals(0.0);
    // int A = 0.5 * 2 + 0.5 * 5; int A s = int_0^.5 (1 + 4s) s + 5 (1 - .25)/2.
    assert!((a - 3.5).abs() < 1e-12, "{a}");
    let exact = 0.125 + 4.0 / 24.0 + 5.0 * 0.375;
    assert!((m - exact).abs() < 1e-12, "{m} vs {exact}");
    let q = t.integrate(0.0, 1.0, 0.0, |s, v, w| v.area * s * w);
    assert!((q - exact).abs() < 1e-12);
    // int ds / I: 0.5 / 2 + 0.5 / 1.
    assert!((t.compliance_integral(0.0, 1.0, |v| v.area_moment) - 0.75).abs() < 1e-12);
}

#[test]
fn errors_name_the_station() {
    let bad_order = SectionTable::new(
        1.0,
        &[st(0.0, 1.0, 1.0), st(0.6, 1.0, 1.0), st(0.4, 1.0, 1.0)],
    );
    let msg = bad_order.unwrap_err().to_string();
    assert!(msg.contains("station 2") && msg.contains("0.4"), "{msg}");
    let short = SectionTable::new(1.0, &[st(0.0, 1.0, 1.0), st(0.9, 1.0, 1.0)]);
    let msg = short.unwrap_err().to_string();
    assert!(
        msg.contains("station 1") && msg.contains("reach C"),
        "{msg}"
    );
    let late = SectionTable::new(1.0, &[st(0.1, 1.0, 1.0), st(1.0, 1.0, 1.0)]);
    assert!(late.unwrap_err().to_string().contains("start at B"));
    let neg = SectionTable::new(1.0, &[st(0.0, 1.0, 1.0), st(1.0, -2.0, 1.0)]);
    let msg = neg.unwrap_err().to_string();
    assert!(
        msg.contains("rod.section.area") && msg.contains("station 1"),
        "{msg}"
    );
    let t = SectionTable::new(1.0, &[st(0.0, 1.0, 1.0), st(1.0, 1.0, 1.0)]).unwrap();
    let msg = t.require_fibre_distance().unwrap_err().to_string();
    assert!(
        msg.contains("fibre_distance") && msg.contains("station 0"),
        "{msg}"
    );
    // Ends within 1e-9 L are accepted and snapped.
    let t = SectionTable::new(1.0, &[st(1e-12, 1.0, 1.0), st(1.0 - 1e-12, 1.0, 1.0)]).unwrap();
    assert_eq!(t.stations()[1].position, 1.0);
}
