//! Hostile inputs at the command line, the scene file reader and the messages, one regression
//! test per contract line: every value that crosses a boundary is checked against a documented
//! range, and a refusal names the value and its range. The runs of the `flexrod` binary that
//! could read or allocate without bound run as child processes with a time limit (killed and
//! failed past it).
//!
//! - a run that would record more than `limits::MAX_POINTS` communication points is refused
//!   naming the flag, the points and the cap (the packager's side: `fmu/tests/cli.rs`);
//! - a scene text with a character XML 1.0 cannot carry is refused naming the key, the
//!   character and its position; XML's special characters and non-ASCII letters are escaped
//!   and read back;
//! - a scene file or `--input` table past its size cap (`/dev/zero`) is refused without
//!   being read to its end;
//! - `--speed` and `--revolutions` are refused with `--input`; the summary counts the
//!   revolutions the crank turned;
//! - echoed input (a TOML line, a CSV line, a flag's value) is cut to `text::ECHO_CHARS`
//!   characters;
//! - messages: the shear area and shear modulus windows name their key, integers print as
//!   integers, the `[experiment]` stop time is named with a range that is never empty, times
//!   print exactly;
//! - docs/fmu.md lists every item of every enumeration the model description declares.

mod common;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use flexrod::fmi::description::ModelDescription;
use flexrod::limits::{CSV_FILE_CAP, MAX_POINTS, SCENE_FILE_CAP};
use flexrod::{ModelError, Scene, Simulation};

/// The outcome of a child process: exit code, stdout, stderr.
struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Run `flexrod ARGS` in the repository, killed and failed past `limit`.
fn flexrod_within(args: &[&str], limit: Duration) -> Outcome {
    let mut child = Command::new(env!("CARGO_BIN_EXE_flexrod"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the flexrod binary runs");
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            String::from_utf8_lossy(&bytes).into_owned()
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("stdout")));
    let stderr = drain(Box::new(child.stderr.take().expect("stderr")));
    let status = common::child::wait_within(&mut child, limit, &format!("flexrod {args:?}"));
    Outcome {
        code: status.code(),
        stdout: stdout.join().expect("stdout read"),
        stderr: stderr.join().expect("stderr read"),
    }
}

fn flexrod(args: &[&str]) -> Outcome {
    flexrod_within(args, Duration::from_secs(120))
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("hostile_inputs_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The benchmark scene's text with `from` replaced by `to` (which must occur).
fn benchmark_with(from: &str, to: &str) -> String {
    let text = flexrod::scene::DEFAULT_SCENE_TOML;
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// `out` exited with `code` and a message under 2000 bytes that holds every one of `parts`.
fn assert_short_refusal(out: &Outcome, code: i32, parts: &[&str]) {
    assert_eq!(
        out.code,
        Some(code),
        "{}",
        &out.stderr[..out.stderr.len().min(2000)]
    );
    assert!(out.stderr.len() < 2000, "{} bytes", out.stderr.len());
    assert_contains(&out.stderr, parts);
}

fn assert_contains(text: &str, parts: &[&str]) {
    for part in parts {
        assert!(text.contains(part), "'{part}' not in\n{text}");
    }
}

/// `flexrod simulate` refuses a run past the shared point cap before it starts,
/// naming the flag, the points it would need and the cap.
#[test]
fn runs_past_the_shared_point_cap_are_refused_naming_the_flag() {
    assert_eq!(MAX_POINTS, 10_000_000);
    let out = flexrod(&["simulate", "--step", "1e-9"]);
    assert_eq!(out.code, Some(2), "{}", out.stderr);
    assert!(out.stdout.is_empty(), "{}", out.stdout);
    assert_contains(
        &out.stderr,
        &[
            "--step 1e-9 s",
            "83800001 communication points",
            "at most 10000000",
        ],
    );
    // The cap itself: one point more than allowed is refused, the cap is not.
    assert!(flexrod::limits::check_points("x", MAX_POINTS as f64).is_ok());
    let e = flexrod::limits::check_points("--steps 1e-9", MAX_POINTS as f64 + 1.0).unwrap_err();
    assert_contains(&e, &["--steps 1e-9", "10000001", "at most 10000000"]);
}

/// The attribute `key` of the first element `element` of `xml`, unescaped.
fn attribute(xml: &str, element: &str, key: &str) -> String {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    loop {
        match reader.read_event().expect("well-formed XML") {
            Event::Start(e) | Event::Empty(e) if e.name().as_ref() == element => {
                for a in e.attributes() {
                    let a = a.expect("a well-formed attribute");
                    if a.key.as_ref() == key {
                        return a
                            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                            .expect("an attribute value")
                            .into_owned();
                    }
                }
                panic!("{element} has no {key}");
            }
            Event::Eof => panic!("no {element}"),
            _ => {}
        }
    }
}

/// A control character in the scene's description or name is refused at scene
/// validation, naming the key, the character and its position; `& < > " '` and non-ASCII
/// letters are escaped and read back unchanged from both model descriptions.
#[test]
fn scene_texts_hold_only_what_xml_carries() {
    let dir = scratch("xml");
    for (key, from, to, character, position) in [
        (
            "description",
            "description = \"Slider-crank",
            "description = \"Sl\\u0007ider-crank",
            "U+0007",
            3,
        ),
        (
            "description",
            "description = \"Slider-crank",
            "description = \"Slider\\n-crank",
            "U+000A",
            7,
        ),
        (
            "name",
            "name = \"FlexibleSliderCrank\"",
            "name = \"Flex\\u001bible\"",
            "U+001B",
            5,
        ),
    ] {
        let scene = write(&dir, "bad.toml", &benchmark_with(from, to));
        let out = flexrod(&["simulate", &scene]);
        assert_eq!(out.code, Some(1), "{key}: {}", out.stderr);
        assert_contains(
            &out.stderr,
            &[
                &format!("{key} holds the character {character} at position {position}"),
                "XML 1.0",
            ],
        );
        let e = Scene::from_toml_str(&benchmark_with(from, to), "bad.toml").unwrap_err();
        assert!(e.to_string().contains(character), "{e}");
    }
    // A scene built in code does not pass the reader: the description refuses it too.
    let mut scene = Scene::benchmark();
    scene.description = "tab\there".into();
    let e = ModelDescription::for_scene(&scene).err().expect("refused");
    assert!(e.to_string().contains("U+0009 at position 4"), "{e}");

    let text = "A <&> \"quoted\" 'rod' & Größe, élan, Ωμέγα";
    let mut scene = Scene::benchmark();
    scene.description = text.into();
    for description in [
        ModelDescription::for_scene(&scene).unwrap(),
        ModelDescription::for_scene_fmi3(&scene).unwrap(),
    ] {
        assert!(
            description.xml.contains("&lt;&amp;&gt;"),
            "{}",
            description.xml
        );
        assert_eq!(
            attribute(&description.xml, "fmiModelDescription", "description"),
            text
        );
    }
}

/// `/dev/zero` as the scene file or the `--input` table is refused at its cap, with
/// the file, the cap and what was read named, without reading it to its end.
#[test]
fn files_past_their_caps_are_refused_without_reading_them_whole() {
    let limit = Duration::from_secs(60);
    let out = flexrod_within(&["simulate", "/dev/zero"], limit);
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert_contains(
        &out.stderr,
        &[
            "/dev/zero",
            &format!("larger than {SCENE_FILE_CAP} bytes (16 MiB)"),
            &format!("{} bytes read", SCENE_FILE_CAP + 1),
        ],
    );
    let out = flexrod_within(&["simulate", "--input", "/dev/zero"], limit);
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert_contains(
        &out.stderr,
        &[
            "the --input table /dev/zero",
            &format!("larger than {CSV_FILE_CAP} bytes (256 MiB)"),
        ],
    );
    // A file within the cap is read.
    let dir = scratch("caps");
    let scene = write(&dir, "scene.toml", flexrod::scene::DEFAULT_SCENE_TOML);
    let text = flexrod::limits::read_text(Path::new(&scene), 100, "the scene file").unwrap_err();
    assert_contains(&text, &["larger than 100 bytes", "101 bytes read"]);
    assert!(Scene::from_file(Path::new(&scene)).is_ok());
}

/// `--speed` and `--revolutions` are refused with `--input` (the table gives the
/// crank's motion), the summary counts the revolutions the table's crank turned, and
/// `--revolutions` with `--ramp` runs that many turns of the ramped crank.
#[test]
fn input_tables_refuse_speed_and_revolutions_and_the_summary_reports_what_ran() {
    let dir = scratch("input");
    // 75 rad/s over the scene's 0.0838 s: 1.00 revolution.
    let table = write(&dir, "table.csv", "t,angle,speed\n0,0,75\n0.1,7.5,75\n");
    for flag in [
        ["--speed", "300"],
        ["--revolutions", "10"],
        ["--ramp", "0.1"],
    ] {
        let out = flexrod(&["simulate", "--input", &table, flag[0], flag[1]]);
        assert_eq!(out.code, Some(2), "{flag:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{flag:?}");
        assert_contains(&out.stderr, &["cannot be used with", flag[0], "--input"]);
    }
    let out = flexrod(&["simulate", "--input", &table]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    assert_contains(&out.stdout, &["(1.00 revolutions of the crank)"]);
    // --revolutions counts the turns of the law that runs, a ramp's slower start included.
    let out = flexrod(&[
        "simulate",
        "--speed",
        "200",
        "--ramp",
        "0.02",
        "--revolutions",
        "4",
    ]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    assert_contains(&out.stdout, &["(4.00 revolutions of the crank)"]);
    let help = flexrod(&["simulate", "--help"]).stdout;
    assert_contains(
        &help,
        &["--speed, --revolutions and --ramp are refused with it"],
    );
}

/// A TOML line of 800 KB and a CSV line of 800 KB are echoed cut to
/// `text::ECHO_CHARS` characters with their length, by the CLI and by the scene reader the
/// packager and the FMU (resources, serialized states) share.
#[test]
fn echoed_input_is_bounded() {
    let dir = scratch("echo");
    let deep = format!("name = \"a\"\nx = {}\n", "[".repeat(800_000));
    let scene = write(&dir, "deep.toml", &deep);
    let out = flexrod(&["simulate", &scene]);
    assert_eq!(
        out.code,
        Some(1),
        "{}",
        &out.stderr[..out.stderr.len().min(2000)]
    );
    assert!(out.stderr.len() < 2000, "{} bytes", out.stderr.len());
    assert_contains(&out.stderr, &["... (800008 bytes)"]);
    let e = Scene::from_toml_str(&deep, "the serialized state").unwrap_err();
    assert!(e.to_string().len() < 2000, "{} bytes", e.to_string().len());
    let key = format!("name = \"a\"\n{} = 1\n", "k".repeat(800_000));
    let e = Scene::from_toml_str(&key, "scene.toml").unwrap_err();
    assert!(e.to_string().len() < 4000, "{} bytes", e.to_string().len());

    let table = write(
        &dir,
        "long.csv",
        &format!("0,0,150\n1,{},150\n", "9".repeat(800_000) + "x"),
    );
    let out = flexrod(&["simulate", "--input", &table]);
    assert_short_refusal(&out, 1, &["line 2", "... (800007 bytes)"]);

    // A flag's value, quoted by the command-line parser.
    let value = "9".repeat(100_000) + "x";
    let out = flexrod(&["simulate", "--speed", &value]);
    assert_short_refusal(&out, 2, &["invalid value", "bytes)"]);
}

/// The messages name the value that is wrong, with its range, printed exactly.
#[test]
fn messages_name_the_wrong_value_with_exact_numbers() {
    // (a) A shear area or modulus that leaves the spectrum unresolvable is refused by name.
    let mut scene = Scene::benchmark();
    scene.rod.shear_deformation = flexrod::rod::PhysicsSwitch::On;
    for a_s in [1e-20, 1e-300, 1e-8] {
        scene.rod.shear_area = Some(a_s);
        let e = Simulation::new(&scene).err().expect("refused").to_string();
        assert_contains(
            &e,
            &[
                "rod.shear_area",
                "[rod.area / 100, rod.area] = [3.167e-7, 3.167e-5] m2",
            ],
        );
    }
    scene.rod.shear_area = Some(3.167e-7);
    assert!(Simulation::new(&scene).is_ok());
    scene.rod.shear_area = None;
    scene.rod.shear_modulus = Some(1e5);
    let e = Simulation::new(&scene).err().expect("refused").to_string();
    assert_contains(
        &e,
        &[
            "rod.shear_modulus",
            "rod.youngs_modulus / 1000 = 2.068e8 Pa",
        ],
    );

    // (b) Integers print as integers.
    let mut scene = Scene::benchmark();
    scene.rod.elements = 129;
    let e = Simulation::new(&scene).err().expect("refused").to_string();
    assert_contains(&e, &["rod.elements = 129 is out of range", "1..=128"]);
    let mut scene = Scene::benchmark();
    scene.solver.max_newton_iterations = 1_000_000_000;
    let e = Scene::from_toml_str(&scene.to_toml(), "scene.toml")
        .unwrap_err()
        .to_string();
    assert_contains(&e, &["max_newton_iterations = 1000000000 is out of range"]);

    // (c) The stop time is named, with a range that is not empty, at every start time.
    for start in [0.0, -1e6, 999_999.0, 1.0] {
        let mut scene = Scene::benchmark();
        scene.experiment.start_time = start;
        // A stop time less than the smallest step after the start.
        scene.experiment.stop_time = if start == 0.0 { 5e-324 } else { start };
        let e = scene.experiment.validate().unwrap_err();
        let ModelError::InvalidParameter { name, allowed, .. } = &e else {
            panic!("{e}")
        };
        assert_eq!(*name, "experiment.stop_time", "start {start}: {e}");
        let range = allowed
            .split(" = [")
            .nth(1)
            .expect("a range")
            .split(']')
            .next()
            .unwrap();
        let bounds: Vec<f64> = range.split(", ").map(|x| x.parse().unwrap()).collect();
        assert!(bounds[0] < bounds[1], "start {start}: empty range in {e}");
        scene.experiment.stop_time = bounds[0];
        scene.experiment.step_size = 1e-9;
        assert!(scene.experiment.validate().is_ok(), "start {start}: {e}");
    }
    let mut scene = Scene::benchmark();
    scene.experiment.start_time = 1e6;
    let e = scene.experiment.validate().unwrap_err().to_string();
    assert_contains(&e, &["experiment.start_time = 1000000", "9.99999e5"]);

    // (d) Times print exactly, however small.
    for (t, text) in [
        (1e-7, "t = 1e-7 s"),
        (1e-13, "t = 1e-13 s"),
        (0.0055, "t = 0.0055 s"),
    ] {
        let e = ModelError::StepFailed {
            time: t,
            step: 1e-4,
            reason: "x".into(),
        };
        assert_contains(&e.to_string(), &[text]);
        let e = ModelError::DeflectionLimit {
            time: t,
            deflection: 0.1,
            limit: 0.05,
            discard: true,
            range: "r",
        };
        assert_contains(&e.to_string(), &[text]);
    }
}

/// docs/fmu.md lists every item of every enumeration the model descriptions declare
/// (name and code in the parameter table, `items 1..N` and `max="N"` in the ranges table).
#[test]
fn docs_list_every_enumeration_item_of_the_model_description() {
    let docs =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/fmu.md")).unwrap();
    let xml = ModelDescription::for_scene(&Scene::benchmark())
        .unwrap()
        .xml;
    let (types, variables) = enumerations(&xml);
    assert!(types.len() >= 3, "{types:?}");
    for (variable, ty) in &variables {
        let items = &types[ty];
        let n = items.len();
        let row = |needle: &str| {
            docs.lines()
                .find(|l| l.starts_with(&format!("| `{variable}`")) && l.contains(needle))
                .unwrap_or_else(|| panic!("docs/fmu.md: no row of {variable} with {needle}"))
                .to_string()
        };
        let parameter_row = row("Enumeration");
        for (k, item) in items.iter().enumerate() {
            let listed = format!("`{item}` = {}", k + 1);
            assert!(
                parameter_row.contains(&listed),
                "docs/fmu.md, {variable}: {listed} missing in\n{parameter_row}"
            );
        }
        let range_row = docs
            .lines()
            .find(|l| l.contains(&format!("`{variable}`")) && l.contains("items 1.."))
            .unwrap_or_else(|| panic!("docs/fmu.md: no range row of {variable}"));
        assert!(
            range_row.contains(&format!("items 1..{n};"))
                && range_row.contains(&format!("max=\"{n}\"")),
            "docs/fmu.md, {variable}: {n} items declared, the range row says\n{range_row}"
        );
    }
}

/// The item names of each enumeration type, by type name, in code order.
type Items = std::collections::BTreeMap<String, Vec<String>>;

/// The items of each enumeration type and the variables that declare one (name, type) in an
/// FMI 2.0 model description.
fn enumerations(xml: &str) -> (Items, Vec<(String, String)>) {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut types = Items::new();
    let mut variables = Vec::new();
    let mut simple_type = None;
    let mut variable = None;
    loop {
        let event = reader.read_event().expect("well-formed XML");
        let element = match &event {
            Event::Start(e) | Event::Empty(e) => e,
            Event::Eof => break,
            _ => continue,
        };
        let get = |key: &str| {
            element
                .attributes()
                .map(|a| a.expect("a well-formed attribute"))
                .find(|a| a.key.as_ref() == key)
                .map(|a| {
                    a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .expect("a value")
                        .into_owned()
                })
        };
        match element.name().as_ref() {
            "SimpleType" => simple_type = get("name"),
            "ScalarVariable" => variable = get("name"),
            "Item" => {
                let ty = simple_type.clone().expect("an item in a type");
                let value: usize = get("value").unwrap().parse().unwrap();
                let items = types.entry(ty).or_default();
                assert_eq!(value, items.len() + 1, "codes in order from 1");
                items.push(get("name").unwrap());
            }
            "Enumeration" => {
                if let (Some(ty), Some(v)) = (get("declaredType"), variable.clone()) {
                    variables.push((v, ty));
                }
            }
            _ => {}
        }
    }
    (types, variables)
}
