//! What README.md and docs/ state about the code is what the code does:
//!
//! - docs/fmu.md's list of the shipped scenes names every `scenes/*.toml` (and no other file)
//!   with the rod model the file sets (`model = "..."`), and its example of the default scene
//!   is `scenes/benchmark.toml` (the same keys and values);
//! - docs/fmu.md's `[experiment]` defaults are the ones a scene without the table gets, in the
//!   model description's `DefaultExperiment` too (that the packager takes such a scene:
//!   fmu/src/package.rs);
//! - every list of the Integer codes of an enumeration (`rod.model_index`: 1 = `ffr`, ...) in
//!   README.md and docs/ gives the codes the FMU's model description declares, all of them
//!   where it lists more than one.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use common::repository;
use flexrod::Scene;

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// The lines of `text` from the heading `heading` (a whole line) to the next heading of the
/// same or a higher level.
fn section<'a>(text: &'a str, heading: &str) -> &'a str {
    let start = text
        .find(&format!("\n{heading}\n"))
        .unwrap_or_else(|| panic!("no heading '{heading}'"))
        + 1;
    let level = heading.chars().take_while(|&c| c == '#').count();
    let body = &text[start + heading.len() + 1..];
    let mut in_fence = false;
    let mut offset = 0;
    for line in body.split_inclusive('\n') {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
        }
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if !in_fence && hashes > 0 && hashes <= level && line[hashes..].starts_with(' ') {
            break;
        }
        offset += line.len();
    }
    &text[start..start + heading.len() + 1 + offset]
}

/// The rod's shipped scenes, `scenes/*.toml`, by file name (the crankshaft's scene has its
/// own section in docs/fmu.md).
fn scene_files() -> BTreeMap<String, PathBuf> {
    std::fs::read_dir(repository().join("scenes"))
        .expect("read scenes/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap_or_default();
            flexrod::fmi::registry::ModelKind::of_scene_text(&text)
                == flexrod::fmi::registry::ModelKind::Rod
        })
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), p))
        .collect()
}

/// The code spans of a Markdown line (text between single backticks).
fn spans(line: &str) -> Vec<&str> {
    line.split('`').skip(1).step_by(2).collect()
}

/// The scene files a row's first cell names: `file.toml`, or a pattern `prefix_<x>.toml` with
/// "`<x>` one of `a`, `b`" expanded.
fn files_of_row(first_cell: &str) -> Vec<String> {
    let names = spans(first_cell);
    let Some(pattern) = names.first() else {
        return Vec::new();
    };
    match (pattern.find('<'), pattern.find('>')) {
        (Some(open), Some(close)) => {
            let placeholder = &pattern[open..=close];
            let values = first_cell
                .split_once("one of")
                .map(|(_, list)| spans(list))
                .unwrap_or_default();
            assert!(
                !values.is_empty(),
                "docs/fmu.md: the pattern {pattern} lists no values"
            );
            values
                .iter()
                .map(|v| pattern.replace(placeholder, v))
                .collect()
        }
        _ => vec![pattern.to_string()],
    }
}

/// docs/fmu.md's table of the shipped scenes lists every scene file with the rod model it sets,
/// and names no file that does not exist.
#[test]
fn the_shipped_scenes_are_listed_with_their_rod_model() {
    let fmu = read(&repository().join("docs/fmu.md"));
    let scenes = section(&fmu, "## Scene files");
    let files = scene_files();
    let mut listed = BTreeMap::new();
    let mut failures = Vec::new();
    for row in scenes
        .lines()
        .skip_while(|l| !l.starts_with("| file |"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
    {
        let cells: Vec<&str> = row.split(" | ").collect();
        for file in files_of_row(cells[0]) {
            let Some(path) = files.get(&file) else {
                failures.push(format!("docs/fmu.md lists {file}: no such file in scenes/"));
                continue;
            };
            let scene = Scene::from_file(path).expect("a shipped scene reads");
            let model = format!("`model = \"{}\"`", scene.rod.model.name());
            if !row.contains(&model) {
                failures.push(format!(
                    "docs/fmu.md, the row of {file}: it sets {model}, the row says otherwise or \
                     nothing:\n{row}"
                ));
            }
            listed.insert(file, ());
        }
    }
    for file in files.keys() {
        if !listed.contains_key(file) {
            failures.push(format!(
                "scenes/{file} is not in docs/fmu.md's list of the shipped scenes"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// docs/fmu.md's "Example: the default scene" has the keys and values of scenes/benchmark.toml.
#[test]
fn the_default_scene_example_is_the_default_scene() {
    let fmu = read(&repository().join("docs/fmu.md"));
    let example = section(&fmu, "### Example: the default scene");
    let block: String = example
        .lines()
        .skip_while(|l| l.trim() != "```toml")
        .skip(1)
        .take_while(|l| l.trim() != "```")
        .map(|l| format!("{l}\n"))
        .collect();
    let shown: toml::Value = toml::from_str(&block).expect("the example parses");
    let file: toml::Value = toml::from_str(&read(&repository().join("scenes/benchmark.toml")))
        .expect("scenes/benchmark.toml parses");
    assert_eq!(
        shown, file,
        "docs/fmu.md's example of the default scene differs from scenes/benchmark.toml"
    );
}

/// docs/fmu.md's `[experiment]` table gives the defaults a scene without the table gets, which
/// are also its model description's `DefaultExperiment`; the text says the table is optional.
#[test]
fn experiment_defaults_are_the_documented_ones() {
    let fmu = read(&repository().join("docs/fmu.md"));
    let keys = section(&fmu, "### Keys");
    let at = keys
        .find("`[experiment]` (optional")
        .expect("docs/fmu.md says [experiment] is optional");
    let paragraph = &keys[at..];
    let mut documented = BTreeMap::new();
    for row in paragraph
        .lines()
        .skip_while(|l| !l.starts_with("| key |"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
    {
        let cells: Vec<&str> = row.split(" | ").collect();
        let key = spans(cells[0])[0].to_string();
        let default: f64 = cells[2]
            .split_whitespace()
            .next()
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("docs/fmu.md, [experiment] {key}: no default in {row}"));
        documented.insert(key, default);
    }
    let benchmark = read(&repository().join("scenes/benchmark.toml"));
    let without = &benchmark[..benchmark.find("[experiment]").expect("a table")];
    let scene = Scene::from_toml_str(without, "benchmark without [experiment]")
        .expect("a scene without [experiment] reads");
    let e = &scene.experiment;
    let code: BTreeMap<String, f64> = [
        ("crank_speed", e.crank_speed),
        ("start_time", e.start_time),
        ("step_size", e.step_size),
        ("stop_time", e.stop_time),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    assert_eq!(documented, code, "docs/fmu.md's [experiment] defaults");
    let description = flexrod::fmi::ModelDescription::for_scene(&scene)
        .expect("a scene without [experiment] has a model description");
    let default_experiment = description
        .xml
        .lines()
        .find(|l| l.contains("<DefaultExperiment"))
        .expect("a DefaultExperiment")
        .to_string();
    for (attribute, value) in [
        ("startTime", e.start_time),
        ("stopTime", e.stop_time),
        ("stepSize", e.step_size),
    ] {
        let quoted = default_experiment
            .split(&format!("{attribute}=\""))
            .nth(1)
            .and_then(|rest| rest.split('"').next())
            .and_then(|v| v.parse::<f64>().ok());
        assert_eq!(quoted, Some(value), "{attribute} in {default_experiment}");
    }
}

/// The enumerations of a model description with an Integer twin (`<name>_index`): the
/// variable's name and its items by code.
fn enumerations_with_twins(xml: &str) -> BTreeMap<String, BTreeMap<u32, String>> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut types: BTreeMap<String, BTreeMap<u32, String>> = BTreeMap::new();
    let mut declared: BTreeMap<String, String> = BTreeMap::new();
    let mut names = Vec::new();
    let (mut simple_type, mut variable) = (None::<String>, None::<String>);
    loop {
        let event = reader
            .read_event()
            .expect("a well-formed model description");
        let (element, is_start) = match &event {
            Event::Start(e) => (e.clone(), true),
            Event::Empty(e) => (e.clone(), false),
            Event::End(e) => {
                match e.name().as_ref() {
                    "SimpleType" => simple_type = None,
                    "ScalarVariable" => variable = None,
                    _ => {}
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let get = |key: &str| {
            element
                .attributes()
                .flatten()
                .find(|a| a.key.as_ref() == key)
                .map(|a| a.value.to_string())
        };
        match element.name().as_ref() {
            "SimpleType" if is_start => simple_type = get("name"),
            "Item" => {
                if let (Some(t), Some(name), Some(value)) =
                    (&simple_type, get("name"), get("value"))
                {
                    types
                        .entry(t.clone())
                        .or_default()
                        .insert(value.parse().expect("an item's value"), name);
                }
            }
            "ScalarVariable" => {
                let name = get("name").expect("a variable's name");
                names.push(name.clone());
                variable = is_start.then_some(name);
            }
            "Enumeration" => {
                if let (Some(v), Some(t)) = (&variable, get("declaredType")) {
                    declared.insert(v.clone(), t);
                }
            }
            _ => {}
        }
    }
    declared
        .into_iter()
        .filter(|(v, _)| names.contains(&format!("{v}_index")))
        .map(|(v, t)| (v, types.get(&t).cloned().unwrap_or_default()))
        .collect()
}

/// `code = name` at the start of `s` (`1 = ffr`, ``2 = `segments` ``): the code, the name and
/// the length read.
fn pair_at(s: &str) -> Option<(u32, String, usize)> {
    let digits = s.bytes().take_while(u8::is_ascii_digit).count();
    let code = s[..digits].parse().ok()?;
    // ` = `, the spaces around `=` possibly more than one (a line break read as a space).
    let after = &s[digits..];
    let rest = after.strip_prefix(' ')?.trim_start().strip_prefix('=')?;
    let rest = rest.strip_prefix(' ')?.trim_start();
    let ticked = rest.starts_with('`');
    let name = rest.trim_start_matches('`');
    let len = name
        .bytes()
        .take_while(|c| c.is_ascii_alphabetic() || *c == b'_')
        .count();
    if len < 2 {
        return None;
    }
    let used = s.len() - name.len() + len + usize::from(ticked && name[len..].starts_with('`'));
    Some((code, name[..len].to_string(), used))
}

/// The codes stated after a mention of an Integer twin, from `after` (the text right after the
/// twin's name, line breaks as spaces): a list `1 = a, 2 = b, ...` starting within 120
/// characters, or one code, `` = 3` (or `rod.model = "b"`) `` or `= 2: b`.
fn stated_codes(after: &str) -> Vec<(u32, String)> {
    // One code set: ` = 3` ... `"name"`, or ` = 2: name`.
    let single = after.trim_start_matches('`');
    if let Some(rest) = single.strip_prefix(" = ") {
        let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
        if let Ok(code) = rest[..digits].parse::<u32>() {
            let tail = &rest[digits..];
            let word = |s: &str| -> String {
                s.chars()
                    .take_while(|c| c.is_ascii_lowercase() || *c == '_')
                    .collect()
            };
            if let Some(name) = tail.strip_prefix(": ").map(word) {
                if name.len() >= 2 {
                    return vec![(code, name)];
                }
            }
            let near: String = tail.chars().take(60).collect();
            if let Some(q) = near.find("= \"") {
                return vec![(code, word(&near[q + 3..]))];
            }
            return Vec::new();
        }
    }
    let mut start = None;
    for (k, _) in after.char_indices().take_while(|(k, _)| *k < 120) {
        let previous_is_digit = after[..k].ends_with(|c: char| c.is_ascii_digit());
        if !previous_is_digit && pair_at(&after[k..]).is_some() {
            start = Some(k);
            break;
        }
    }
    let Some(mut k) = start else {
        return Vec::new();
    };
    let mut pairs = Vec::new();
    while let Some((code, name, used)) = pair_at(&after[k..]) {
        pairs.push((code, name));
        k += used;
        match after[k..].strip_prefix(',') {
            Some(rest) if rest.starts_with(' ') => k = after.len() - rest.trim_start().len(),
            _ => break,
        }
    }
    pairs
}

/// What is wrong with the codes stated after a mention of `variable`'s twin.
fn code_problems(stated: &[(u32, String)], items: &BTreeMap<u32, String>) -> Vec<String> {
    let mut problems = Vec::new();
    for (code, name) in stated {
        if items.get(code) != Some(name) {
            problems.push(format!(
                "{code} = {name}, the FMU declares {code} = {}",
                items.get(code).map_or("nothing", String::as_str)
            ));
        }
    }
    if stated.len() > 1 && stated.len() != items.len() {
        problems.push(format!(
            "lists {} of its {} codes ({})",
            stated.len(),
            items.len(),
            items
                .iter()
                .map(|(c, n)| format!("{c} = {n}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    problems
}

/// README.md and the Markdown files under docs/ (docs/generated too: its tables come from the
/// model description but are read like the rest).
fn markdown_files() -> Vec<PathBuf> {
    let mut files = vec![repository().join("README.md")];
    let mut stack = vec![repository().join("docs")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn enumeration_codes_in_the_docs_are_the_fmus() {
    let xml = read(&repository().join("modelDescription/modelDescription.xml"));
    let enumerations = enumerations_with_twins(&xml);
    assert!(
        enumerations.contains_key("rod.model") && enumerations.contains_key("rod.reference"),
        "{enumerations:?}"
    );
    let mut failures = Vec::new();
    let mut checked = 0;
    for file in markdown_files() {
        let text = read(&file);
        // Line breaks as spaces: a list may go on over the lines of its paragraph.
        let flat = text.replace('\n', " ");
        let name = file.strip_prefix(repository()).unwrap_or(&file).display();
        for (variable, items) in &enumerations {
            let twin = format!("{variable}_index");
            for (at, _) in flat.match_indices(&twin) {
                let end = at + twin.len();
                // Up to the next table row or paragraph.
                let stop = ["\n|", "\n\n"]
                    .iter()
                    .filter_map(|s| text[end..].find(s))
                    .min()
                    .unwrap_or(text.len() - end);
                let stated = stated_codes(&flat[end..end + stop]);
                if stated.is_empty() {
                    continue;
                }
                checked += 1;
                let line = text[..at].matches('\n').count() + 1;
                for problem in code_problems(&stated, items) {
                    failures.push(format!("{name}:{line}: {twin}: {problem}"));
                }
            }
        }
    }
    println!("{checked} lists of enumeration codes checked");
    assert!(checked >= 4, "only {checked} lists of codes found");
    assert!(
        failures.is_empty(),
        "codes of the Integer twins in README.md and docs/ that are not the model description's:\n{}",
        failures.join("\n")
    );
}

#[test]
fn codes_are_read_as_written() {
    assert_eq!(
        stated_codes("` (vr 114; 1 = ffr, 2 = `segments`, 3 = modal_segments) and 5 = x"),
        [
            (1, "ffr".to_string()),
            (2, "segments".to_string()),
            (3, "modal_segments".to_string())
        ]
    );
    assert_eq!(
        stated_codes(" = 3` (or `rod.model = \"modal_segments\"`),"),
        [(3, "modal_segments".to_string())]
    );
    assert_eq!(
        stated_codes(" = 2: segments"),
        [(2, "segments".to_string())]
    );
    assert!(stated_codes("` | 114 | Integer, `min=\"1\" max=\"4\"` | 4 |").is_empty());
    // Names other than the items' are read as names, and fail below.
    assert_eq!(
        stated_codes("`: 1 = FFR, 2 = segment chain; importers"),
        [(1, "FFR".to_string()), (2, "segment".to_string())]
    );
    let items: BTreeMap<u32, String> = [
        (1, "ffr"),
        (2, "segments"),
        (3, "modal_segments"),
        (4, "auto"),
    ]
    .into_iter()
    .map(|(c, n)| (c, n.to_string()))
    .collect();
    assert_eq!(
        code_problems(&[(1, "ffr".into()), (2, "segments".into())], &items),
        ["lists 2 of its 4 codes (1 = ffr, 2 = segments, 3 = modal_segments, 4 = auto)"]
    );
    assert_eq!(
        code_problems(&[(2, "ffr".into())], &items),
        ["2 = ffr, the FMU declares 2 = segments"]
    );
    assert_eq!(
        files_of_row("| `a_<x>.toml`, `<x>` one of `p`, `q`"),
        ["a_p.toml", "a_q.toml"]
    );
}
