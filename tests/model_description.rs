//! The golden copy `modelDescription/modelDescription.xml` is what the code generates for
//! `scenes/benchmark.toml` now. After an intended change, regenerate it with
//! `FLEXROD_BLESS=1 cargo test --release --test model_description` and review the diff.

use std::path::Path;

use flexrod::fmi::ModelDescription;
use flexrod::Scene;

#[test]
fn golden_model_description_is_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene =
        Scene::from_file(&root.join("scenes/benchmark.toml")).expect("the default scene parses");
    let generated = ModelDescription::for_scene(&scene)
        .expect("the default scene builds")
        .xml;
    let golden_path = root.join("modelDescription/modelDescription.xml");
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
            "{} is out of date ({first_difference}); regenerate with FLEXROD_BLESS=1 cargo test --release --test model_description",
            golden_path.display()
        );
    }
}

#[test]
fn guid_is_stable_and_changes_with_the_scene() {
    let scene = Scene::benchmark();
    let a = ModelDescription::for_scene(&scene).unwrap();
    let b = ModelDescription::for_scene(&scene).unwrap();
    assert_eq!(a.guid, b.guid);
    let mut other = scene.clone();
    other.experiment.step_size = 2e-4;
    assert_ne!(ModelDescription::for_scene(&other).unwrap().guid, a.guid);
}
