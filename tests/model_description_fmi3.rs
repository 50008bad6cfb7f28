//! The FMI 3.0 description: the golden copy
//! `modelDescription/modelDescription-fmi3.xml` is what the code generates for
//! `scenes/benchmark.toml` now (regenerate with
//! `FLEXROD_BLESS=1 cargo test --release --test model_description_fmi3` and review the diff),
//! and its content follows from the one variable table: the FMI 2.0 variables under the same
//! names and value references, the frequencies as one array, the FMI 3.0 additions at value
//! references 150..199, and the FMI 2.0 description unchanged by the FMI 3.0 one.

use std::path::Path;

use flexrod::fmi::variables::{Causality, ValueType};
use flexrod::fmi::{ModelDescription, Standard};
use flexrod::model::variables::{Access, VariableTable};
use flexrod::Scene;

#[test]
fn golden_fmi3_model_description_is_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene =
        Scene::from_file(&root.join("scenes/benchmark.toml")).expect("the default scene parses");
    let generated = ModelDescription::for_scene_fmi3(&scene)
        .expect("the default scene builds")
        .xml;
    let golden_path = root.join("modelDescription/modelDescription-fmi3.xml");
    if std::env::var_os("FLEXROD_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&golden_path, &generated).expect("write the golden copy");
    }
    let golden = std::fs::read_to_string(&golden_path).expect("read the golden copy");
    if golden != generated {
        let first_difference = golden
            .lines()
            .zip(generated.lines())
            .enumerate()
            .find(|(_, (a, b))| a != b)
            .map(|(i, (a, b))| format!("line {}:\n  golden:    {a}\n  generated: {b}", i + 1))
            .unwrap_or_else(|| "the files differ in length".to_string());
        panic!(
            "{} is out of date ({first_difference}); regenerate with FLEXROD_BLESS=1 cargo test --release --test model_description_fmi3",
            golden_path.display()
        );
    }
}

#[test]
fn fmi3_description_from_the_same_table() {
    let scene = Scene::benchmark();
    let d2 = ModelDescription::for_scene(&scene).unwrap();
    let d3 = ModelDescription::for_scene_fmi3(&scene).unwrap();
    assert_eq!(d2.standard(), Standard::Fmi2);
    assert_eq!(d3.standard(), Standard::Fmi3);
    assert!(d3.xml.contains("fmiVersion=\"3.0\""));
    assert!(d3
        .xml
        .contains(&format!("instantiationToken=\"{}\"", d3.guid)));
    assert!(!d3.xml.contains("guid="));
    assert_ne!(d2.guid, d3.guid);
    // Every FMI 2.0 variable but the scalar frequencies is there, same reference and causality.
    let t2 = VariableTable::for_scene(&scene, Standard::Fmi2.interface()).unwrap();
    let t3 = VariableTable::for_scene(&scene, Standard::Fmi3.interface()).unwrap();
    assert_eq!(t2.declarations(), &d2.table);
    assert_eq!(t3.declarations(), &d3.table);
    for v in t2.variables() {
        if matches!(v.access, Access::Frequency(_)) {
            assert!(d3.table.by_name(&v.name).is_none(), "{}", v.name);
            continue;
        }
        let w = d3
            .table
            .by_name(&v.name)
            .unwrap_or_else(|| panic!("{}", v.name));
        assert_eq!(w.value_reference, v.value_reference, "{}", v.name);
        assert_eq!(w.causality, v.causality, "{}", v.name);
        assert_eq!(w.dimension, None, "{}", v.name);
    }
    // The additions.
    let k = t2.frequency_count();
    assert_eq!(k, 6);
    assert_eq!(t3.frequency_count(), k);
    let freq = d3.table.by_name("rod.frequency").unwrap();
    assert_eq!((freq.value_reference, freq.dimension), (153, Some(k)));
    assert_eq!(freq.causality, Causality::CalculatedParameter);
    let shape = d3.table.by_name("rod.shape").unwrap();
    assert_eq!((shape.value_reference, shape.dimension), (152, Some(11)));
    assert_eq!(shape.causality, Causality::Output);
    let acc = d3.table.by_name("crank.acceleration").unwrap();
    assert_eq!(
        (acc.value_reference, acc.causality),
        (151, Causality::Input)
    );
    assert!(matches!(
        acc.value_type,
        ValueType::Real {
            unit: Some("rad/s2"),
            ..
        }
    ));
    let time = d3.table.by_name("time").unwrap();
    assert_eq!(
        (time.value_reference, time.causality),
        (150, Causality::Independent)
    );
    for v in d3.table.variables() {
        if d2.table.by_name(&v.name).is_none() {
            assert!((150..200).contains(&v.value_reference), "{}", v.name);
        }
    }
    // FMI 3.0 types and elements.
    assert!(d3.xml.contains("<Dimension start=\"11\"/>"));
    assert!(d3.xml.contains("<Dimension start=\"6\"/>"));
    assert!(d3.xml.contains("<EnumerationType name=\"RodModel\""));
    assert!(d3.xml.contains("<Int32 name=\"rod.elements\""));
    assert!(d3.xml.contains("causality=\"independent\""));
    assert!(d3.xml.contains("<InitialUnknown valueReference=\"153\""));
    assert!(d3.xml.contains("canGetAndSetFMUState=\"true\""));
    assert!(
        !d3.xml.contains("fmi2"),
        "FMI 2.0 names in the FMI 3.0 description"
    );
    assert!(!d2.xml.contains("crank.acceleration"));
}

#[test]
fn shape_points_is_a_scene_key_with_a_range() {
    let mut scene = Scene::benchmark();
    scene.outputs.shape_points = 0;
    let d = ModelDescription::for_scene_fmi3(&scene).unwrap();
    assert!(d.table.by_name("rod.shape").is_none());
    scene.outputs.shape_points = 21;
    let d = ModelDescription::for_scene_fmi3(&scene).unwrap();
    assert_eq!(d.table.by_name("rod.shape").unwrap().dimension, Some(21));
    // The FMI 2.0 description does not depend on it.
    assert_eq!(
        ModelDescription::for_scene(&scene).unwrap().guid,
        ModelDescription::for_scene(&Scene::benchmark())
            .unwrap()
            .guid
    );
    for bad in [1, 1002] {
        scene.outputs.shape_points = bad;
        let e = ModelDescription::for_scene_fmi3(&scene).err().unwrap();
        assert!(e.to_string().contains("shape_points"), "{e}");
    }
    let text =
        flexrod::scene::DEFAULT_SCENE_TOML.replace("[outputs]", "[outputs]\nshape_points = 5");
    let parsed = Scene::from_toml_str(&text, "test").unwrap();
    assert_eq!(parsed.outputs.shape_points, 5);
}

/// The middle sample of an odd `rod.shape` is `rod.deflection` to the bit at every step, also
/// where the output's evaluation takes accelerations of its own (every mode of a 4-element FFR
/// rod retained; the automotive rod's residual flexibility above its mode band).
#[test]
fn shape_midpoint_is_the_deflection_output_to_the_bit() {
    use flexrod::simulation::CrankInput;
    use flexrod::Simulation;
    let all_modes = flexrod::scene::DEFAULT_SCENE_TOML
        .replace("model = \"auto\"", "model = \"ffr\"")
        .replace("elements = 8", "elements = 4")
        .replace("modes = 3", "modes = 12");
    let automotive = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/automotive_rod.toml"),
    )
    .unwrap();
    for (name, text, speed) in [
        ("4 elements, 12 modes", all_modes, 150.0),
        ("automotive", automotive, 628.3),
    ] {
        let scene = Scene::from_toml_str(&text, name).unwrap();
        let mut sim = Simulation::new(&scene).unwrap();
        let input = CrankInput {
            angle: 0.0,
            speed,
            acceleration: 0.0,
            jerk: 0.0,
        };
        sim.start(0.0, input, 0.0).unwrap();
        let mut shape = [f64::NAN; 9];
        for step in 0..20 {
            sim.advance(1e-4).unwrap();
            sim.mechanism().deflection_shape(sim.state(), &mut shape);
            let v_mid = sim.outputs().deflection;
            assert!(v_mid != 0.0, "{name}: step {step}");
            assert_eq!(
                shape[4].to_bits(),
                v_mid.to_bits(),
                "{name}: step {step}: rod.shape's midpoint {} against rod.deflection {v_mid}",
                shape[4]
            );
        }
    }
}

/// `rod.shape` (Mechanism::deflection_shape): 0 at both ends, `v_mid` in the middle of an odd
/// count, and RodBody::point_at at the ends and the midpoint equal to the named points, for
/// both rod models, after 2 ms at 150 rad/s (a deflected rod).
#[test]
fn shape_matches_the_midpoint_deflection() {
    use flexrod::rod::RodPoint;
    use flexrod::simulation::CrankInput;
    use flexrod::Simulation;
    for model in ["ffr", "segments"] {
        let text = flexrod::scene::DEFAULT_SCENE_TOML
            .replace("model = \"ffr\"", &format!("model = \"{model}\""));
        let scene = Scene::from_toml_str(&text, model).unwrap();
        let mut sim = Simulation::new(&scene).unwrap();
        let input = CrankInput {
            angle: 0.0,
            speed: 150.0,
            acceleration: 0.0,
            jerk: 0.0,
        };
        sim.start(0.0, input, 0.0).unwrap();
        for _ in 0..20 {
            sim.advance(1e-4).unwrap();
        }
        let v_mid = sim.outputs().deflection;
        assert!(v_mid.abs() > 1e-7, "{model}: {v_mid}");
        let mut shape = [f64::NAN; 11];
        sim.mechanism().deflection_shape(sim.state(), &mut shape);
        assert_eq!(shape[0], 0.0);
        assert_eq!(shape[10], 0.0);
        assert_eq!(shape[5], v_mid, "{model}");
        // Neighbours of the midpoint: smaller, same sign (a first-mode-like shape).
        for i in [3, 4, 6, 7] {
            assert!(
                shape[i] * v_mid > 0.0 && shape[i].abs() < v_mid.abs(),
                "{model}: {shape:?}"
            );
        }
        // An even count has no midpoint sample; its two middle samples bracket v_mid.
        let mut even = [0.0; 10];
        sim.mechanism().deflection_shape(sim.state(), &mut even);
        assert!(
            even[4].abs() < v_mid.abs() && even[5].abs() < v_mid.abs(),
            "{model}"
        );
        let rod = &sim.mechanism().rod;
        let q = &sim.state().dae.q;
        let l = rod.length();
        for (s, p) in [(0.0, RodPoint::B), (0.5 * l, RodPoint::Mid)] {
            let d = (rod.point_at(s, q) - rod.point(p, q)).norm();
            assert!(d <= 1e-14 * l, "{model}: point_at({s}) is {d} m from {p:?}");
        }
        // C: up to the FFR rod's chord foreshortening, second order in the deflection
        // (about pi^2 v_mid^2 / (4 L) for a half-sine shape).
        let d = (rod.point_at(l, q) - rod.point(RodPoint::C, q)).norm();
        assert!(
            d <= 3.0 * v_mid * v_mid / l,
            "{model}: point_at(L) is {d} m from C (v_mid = {v_mid} m)"
        );
    }
}
