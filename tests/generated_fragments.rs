//! Generated fragments are current where they are embedded.
//!
//! Convention (details in `tests/common/mod.rs`): a number measured by a program or a test
//! lives in a fragment `docs/generated/<id>.md` that the program or test writes; README.md and
//! the Markdown files under docs/ embed it between the whole lines
//! `<!-- generated: <id> -->` and `<!-- end generated: <id> -->`, the text between them byte for
//! byte the fragment's. This test reads README.md and every `.md` file under docs/ (recursively,
//! docs/generated itself excluded) and fails when
//!
//! - an embedded block differs from its fragment, or its fragment does not exist;
//! - a marker is unterminated, nested, or an end marker has no start;
//! - a file in docs/generated is not embedded anywhere (an orphan), or is not `<id>.md`.
//!
//! Markers inside fenced code blocks (outside a generated block) are text, not markers.
//! `FLEXROD_BLESS=1 cargo test --release --test generated_fragments` rewrites every embedded
//! block from its fragment instead (missing fragments and orphans still fail).

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::{blessing, fragment_path, generated_dir, is_fragment_id, line_diff, repository};

/// A generated block in a Markdown file.
#[derive(Debug, PartialEq)]
struct Block {
    id: String,
    /// 1-based line of the start marker.
    line: usize,
    /// Byte range of the embedded text (from after the start marker's line to the start of
    /// the end marker's line).
    content: std::ops::Range<usize>,
}

#[derive(Debug, PartialEq)]
enum Marker {
    Start(String),
    End(String),
}

/// The marker a whole line is, if any (`Err` for a marker with a malformed id).
fn marker(line: &str) -> Result<Option<Marker>, String> {
    let line = line.trim();
    let Some(inner) = line
        .strip_prefix("<!--")
        .and_then(|s| s.strip_suffix("-->"))
        .map(str::trim)
    else {
        return Ok(None);
    };
    let (id, start) = if let Some(id) = inner.strip_prefix("end generated:") {
        (id.trim(), false)
    } else if let Some(id) = inner.strip_prefix("generated:") {
        (id.trim(), true)
    } else {
        return Ok(None);
    };
    if !is_fragment_id(id) {
        return Err(format!("malformed fragment id '{id}' in '{line}'"));
    }
    Ok(Some(if start {
        Marker::Start(id.to_string())
    } else {
        Marker::End(id.to_string())
    }))
}

/// The generated blocks of `text`, or the first structural error (with its line).
fn blocks(text: &str) -> Result<Vec<Block>, String> {
    let mut found = Vec::new();
    let mut open: Option<(String, usize, usize)> = None; // id, line, content start
    let mut in_fence = false;
    let mut offset = 0;
    for (k, raw) in text.split_inclusive('\n').enumerate() {
        let line_number = k + 1;
        let start_of_line = offset;
        offset += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        if open.is_none() {
            let trimmed = line.trim_start();
            if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
                in_fence = !in_fence;
                continue;
            }
            if in_fence {
                continue;
            }
        }
        let m = marker(line).map_err(|e| format!("line {line_number}: {e}"))?;
        match (m, &open) {
            (None, _) => {}
            (Some(Marker::Start(id)), None) => open = Some((id, line_number, offset)),
            (Some(Marker::End(id)), Some((open_id, line, content_start))) if id == *open_id => {
                found.push(Block {
                    id,
                    line: *line,
                    content: *content_start..start_of_line,
                });
                open = None;
            }
            (Some(m), Some((open_id, line, _))) => {
                return Err(format!(
                    "line {line_number}: {m:?} inside the block '{open_id}' opened at line {line}"
                ))
            }
            (Some(Marker::End(id)), None) => {
                return Err(format!(
                    "line {line_number}: end of '{id}' without its start"
                ))
            }
        }
    }
    match open {
        Some((id, line, _)) => Err(format!("line {line}: block '{id}' is never ended")),
        None => Ok(found),
    }
}

/// README.md and every .md file under docs/ except docs/generated, sorted.
fn markdown_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, skip: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                if path != skip {
                    walk(&path, skip, out);
                }
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut files = vec![repository().join("README.md")];
    walk(&repository().join("docs"), &generated_dir(), &mut files);
    files.sort();
    files
}

fn relative(path: &Path) -> String {
    path.strip_prefix(repository())
        .unwrap_or(path)
        .display()
        .to_string()
}

#[test]
fn embedded_fragments_are_current_and_none_is_orphaned() {
    let mut failures = Vec::new();
    let mut embedded = BTreeSet::new();
    for path in markdown_files() {
        let name = relative(&path);
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {name}: {e}"));
        let found = match blocks(&text) {
            Ok(b) => b,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let mut blessed = String::with_capacity(text.len());
        let mut copied_to = 0;
        for block in &found {
            embedded.insert(block.id.clone());
            let Ok(fragment) = std::fs::read_to_string(fragment_path(&block.id)) else {
                failures.push(format!(
                    "{name}:{}: block '{}' has no docs/generated/{}.md",
                    block.line, block.id, block.id
                ));
                continue;
            };
            let embedded_text = &text[block.content.clone()];
            if embedded_text == fragment {
                continue;
            }
            if blessing() {
                blessed.push_str(&text[copied_to..block.content.start]);
                blessed.push_str(&fragment);
                copied_to = block.content.end;
            } else {
                failures.push(format!(
                    "{name}:{}: block '{}' differs from docs/generated/{}.md (- embedded, + \
                     fragment; lines counted from the start marker):\n{}",
                    block.line,
                    block.id,
                    block.id,
                    line_diff(embedded_text, &fragment, 40)
                ));
            }
        }
        if copied_to > 0 {
            blessed.push_str(&text[copied_to..]);
            std::fs::write(&path, blessed).unwrap_or_else(|e| panic!("cannot write {name}: {e}"));
            eprintln!("blessed the generated blocks of {name}");
        }
    }
    if let Ok(entries) = std::fs::read_dir(generated_dir()) {
        let mut names: Vec<_> = entries.flatten().map(|e| e.path()).collect();
        names.sort();
        for path in names {
            let id = path
                .file_name()
                .and_then(|n| n.to_str())
                .and_then(|n| n.strip_suffix(".md"))
                .filter(|id| is_fragment_id(id) && path.is_file());
            match id {
                None => failures.push(format!(
                    "{}: not a fragment (docs/generated holds only <id>.md files)",
                    relative(&path)
                )),
                Some(id) if !embedded.contains(id) => failures.push(format!(
                    "{}: orphan: embedded in no Markdown file (add `<!-- generated: {id} -->` \
                     ... `<!-- end generated: {id} -->` where it belongs, or delete it and what \
                     writes it)",
                    relative(&path)
                )),
                Some(_) => {}
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} problem(s) with generated fragments:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn blocks_are_parsed_as_whole_lines() {
    let text = "intro\n<!-- generated: a-1 -->\n| x |\n<!-- end generated: a-1 -->\n\
                ```\n<!-- generated: in-fence -->\n```\n\
                <!-- generated: empty -->\n<!-- end generated: empty -->\ntail `<!-- generated: b -->`\n";
    let b = blocks(text).unwrap();
    assert_eq!(b.len(), 2);
    assert_eq!((b[0].id.as_str(), b[0].line), ("a-1", 2));
    assert_eq!(&text[b[0].content.clone()], "| x |\n");
    assert_eq!(
        (b[1].id.as_str(), &text[b[1].content.clone()]),
        ("empty", "")
    );
    let crlf = "<!-- generated: c -->\r\nx\r\n<!-- end generated: c -->\r\n";
    assert_eq!(&crlf[blocks(crlf).unwrap()[0].content.clone()], "x\r\n");
    for (bad, says) in [
        ("<!-- generated: a -->\nx\n", "never ended"),
        ("<!-- end generated: a -->\n", "without its start"),
        (
            "<!-- generated: a -->\n<!-- generated: b -->\n<!-- end generated: b -->\n",
            "inside the block 'a'",
        ),
        (
            "<!-- generated: a -->\n<!-- end generated: b -->\n",
            "inside the block 'a'",
        ),
        ("<!-- generated: Report_X -->\n", "malformed"),
    ] {
        let e = blocks(bad).unwrap_err();
        assert!(e.contains(says), "{bad:?}: {e}");
    }
}

#[test]
fn line_diff_names_the_differing_lines() {
    let d = line_diff("a\nb\nc\n", "a\nB\nc\nd\n", 10);
    assert_eq!(d, "-   2: b\n+   2: B\n+   4: d");
    assert!(line_diff("a", "a\n", 10).contains("final newline"));
}

#[test]
fn check_generated_accepts_a_current_fragment_and_shows_a_stale_line() {
    if blessing() {
        return; // blessing would write the altered text below
    }
    let Some(path) = std::fs::read_dir(generated_dir())
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .min()
    else {
        return;
    };
    let id = path.file_stem().unwrap().to_str().unwrap().to_string();
    let text = std::fs::read_to_string(&path).unwrap();
    common::check_generated(&id, &text);
    common::check_generated(&id, text.trim_end_matches('\n'));
    let stale = format!("{text}| one more line |\n");
    let panic = std::panic::catch_unwind(|| common::check_generated(&id, &stale)).unwrap_err();
    let message = panic.downcast_ref::<String>().expect("a formatted message");
    let added = format!("+{:>4}: | one more line |", text.lines().count() + 1);
    assert!(
        message.contains("is stale") && message.contains(&added),
        "{message}"
    );
}

/// One `ScalarVariable` of a model description, as the README's variable table shows it.
#[derive(Debug, Default, Clone, PartialEq)]
struct Variable {
    name: String,
    value_reference: String,
    causality: String,
    description: String,
    /// `Real`, `Integer`, `Enumeration`, ...
    kind: String,
    declared_type: String,
    unit: String,
    min: String,
    max: String,
    start: String,
}

/// The variables of a model description, and the items of each enumeration type
/// (`name=value` pairs, by type name).
fn model_variables(xml: &str) -> (Vec<Variable>, std::collections::BTreeMap<String, String>) {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut variables = Vec::new();
    let mut enums = std::collections::BTreeMap::new();
    let mut current: Option<Variable> = None;
    let mut simple_type: Option<String> = None;
    let attributes = |e: &quick_xml::events::BytesStart| -> Vec<(String, String)> {
        e.attributes()
            .map(|a| {
                let a = a.expect("a well-formed attribute");
                (
                    a.key.as_ref().to_string(),
                    a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .expect("an attribute value")
                        .into_owned(),
                )
            })
            .collect()
    };
    loop {
        let event = reader
            .read_event()
            .expect("a well-formed model description");
        let (element, empty) = match &event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(e) => {
                match e.name().as_ref() {
                    "ScalarVariable" => variables.extend(current.take()),
                    "SimpleType" => simple_type = None,
                    _ => {}
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let attrs = attributes(element);
        let get = |key: &str| {
            attrs
                .iter()
                .find(|(k, _)| k == key)
                .map(|(_, v)| v.clone())
                .unwrap_or_default()
        };
        match element.name().as_ref() {
            "SimpleType" if !empty => simple_type = Some(get("name")),
            "Item" => {
                if let Some(t) = &simple_type {
                    let items: &mut String = enums.entry(t.clone()).or_default();
                    if !items.is_empty() {
                        items.push_str(", ");
                    }
                    items.push_str(&format!("`{}`={}", get("name"), get("value")));
                }
            }
            "ScalarVariable" => {
                let v = Variable {
                    name: get("name"),
                    value_reference: get("valueReference"),
                    causality: get("causality"),
                    description: get("description"),
                    ..Default::default()
                };
                if empty {
                    variables.push(v);
                } else {
                    current = Some(v);
                }
            }
            kind @ ("Real" | "Integer" | "Enumeration" | "Boolean" | "String") => {
                if let Some(v) = current.as_mut() {
                    v.kind = kind.to_string();
                    v.declared_type = get("declaredType");
                    v.unit = get("unit");
                    v.min = get("min");
                    v.max = get("max");
                    v.start = get("start");
                }
            }
            _ => {}
        }
    }
    (variables, enums)
}

/// A model description's number as the table shows it: `206800000000.0` as `2.068e11`,
/// `0.0` as `0`.
fn plain_number(s: &str) -> String {
    match s.parse::<f64>() {
        Ok(0.0) => "0".into(),
        Ok(x) if x.abs() >= 1e5 || x.abs() < 1e-3 => {
            let e = format!("{x:e}");
            e.replace("e-0", "e-")
        }
        Ok(x) => format!("{x}"),
        Err(_) => s.to_string(),
    }
}

/// The README's variable table: one row per variable of the default scene's committed model
/// description (`modelDescription/modelDescription.xml`, kept identical to what the code
/// generates by `tests/model_description.rs`); array elements `name[1]`, `name[2]`, ... that
/// differ only in their index share one row.
fn variable_table(xml: &str) -> String {
    let (variables, enums) = model_variables(xml);
    let mut out = String::from(
        "<!-- written by `FLEXROD_BLESS=1 cargo test --release --test generated_fragments variable_table` from modelDescription/modelDescription.xml: rerun it, do not edit -->\n\
         | name | vr | causality | type, unit | range | start | description |\n\
         |---|---|---|---|---|---|---|\n",
    );
    let base = |name: &str| -> Option<(String, u32)> {
        let (stem, rest) = name.split_once('[')?;
        let k = rest.strip_suffix(']')?.parse().ok()?;
        Some((stem.to_string(), k))
    };
    // An Enumeration's Integer twin `<name>_index` shares its row.
    let twin_of = |name: &str| {
        variables
            .iter()
            .find(|w| w.name == format!("{name}_index") && w.kind == "Integer")
    };
    let is_twin = |name: &str| {
        name.strip_suffix("_index").is_some_and(|stem| {
            variables
                .iter()
                .any(|w| w.name == stem && w.kind == "Enumeration")
        })
    };
    let mut k = 0;
    while k < variables.len() {
        let v = &variables[k];
        if is_twin(&v.name) {
            k += 1;
            continue;
        }
        // A run of array elements stem[1], stem[2], ... with the same attributes.
        let mut last = k;
        if let Some((stem, 1)) = base(&v.name) {
            while last + 1 < variables.len() {
                let w = &variables[last + 1];
                let same = base(&w.name) == Some((stem.clone(), (last + 2 - k) as u32))
                    && (&w.causality, &w.kind, &w.unit, &w.min, &w.max, &w.start)
                        == (&v.causality, &v.kind, &v.unit, &v.min, &v.max, &v.start);
                if !same {
                    break;
                }
                last += 1;
            }
        }
        let (name, vr, description) = if last > k {
            let (stem, _) = base(&v.name).unwrap();
            (
                format!("`{stem}[k]`, k = 1..{}", last - k + 1),
                format!("{}..{}", v.value_reference, variables[last].value_reference),
                v.description.replace(" 1 ", " k "),
            )
        } else if let Some(twin) = twin_of(&v.name).filter(|_| v.kind == "Enumeration") {
            (
                format!("`{}`, `{}`", v.name, twin.name),
                format!("{}, {}", v.value_reference, twin.value_reference),
                format!("{} (Integer twin: the same values as codes)", v.description),
            )
        } else {
            (
                format!("`{}`", v.name),
                v.value_reference.clone(),
                v.description.clone(),
            )
        };
        let kind = if v.unit.is_empty() {
            v.kind.clone()
        } else {
            format!("{}, {}", v.kind, v.unit)
        };
        let range = if v.kind == "Enumeration" {
            enums.get(&v.declared_type).cloned().unwrap_or_default()
        } else {
            match (v.min.is_empty(), v.max.is_empty()) {
                (true, true) => String::new(),
                (false, true) => format!(">= {}", plain_number(&v.min)),
                (true, false) => format!("<= {}", plain_number(&v.max)),
                (false, false) => {
                    format!("{} .. {}", plain_number(&v.min), plain_number(&v.max))
                }
            }
        };
        let start = if v.start.is_empty() {
            String::new()
        } else {
            plain_number(&v.start)
        };
        out += &format!(
            "| {name} | {vr} | {} | {kind} | {range} | {start} | {} |\n",
            v.causality,
            description.replace('|', "\\|")
        );
        k = last + 1;
    }
    out
}

#[test]
fn variable_table_is_the_model_descriptions() {
    let xml = std::fs::read_to_string(repository().join("modelDescription/modelDescription.xml"))
        .expect("read modelDescription/modelDescription.xml");
    let table = variable_table(&xml);
    for name in [
        "solver.tolerance",
        "rod.deflection_limit",
        "rod.deflection_policy",
        "crank.angle",
    ] {
        assert!(
            table.contains(&format!("`{name}`")),
            "{name} missing:\n{table}"
        );
    }
    common::check_generated("variables", &table);
}

#[test]
fn variable_table_reads_every_kind_of_variable() {
    let xml = r#"<fmiModelDescription><TypeDefinitions>
      <SimpleType name="M"><Enumeration><Item name="a" value="1"/><Item name="b" value="2"/></Enumeration></SimpleType>
      </TypeDefinitions><ModelVariables>
      <ScalarVariable name="x" valueReference="1" description="X &amp; Y" causality="input"><Real unit="m" min="0.0" start="206800000000.0"/></ScalarVariable>
      <ScalarVariable name="m" valueReference="2" description="model" causality="parameter"><Enumeration declaredType="M" start="1"/></ScalarVariable>
      <ScalarVariable name="m_index" valueReference="3" description="m as an Integer" causality="parameter"><Integer min="1" max="2" start="1"/></ScalarVariable>
      <ScalarVariable name="f[1]" valueReference="11" description="Frequency 1 of it" causality="calculatedParameter"><Real unit="Hz"/></ScalarVariable>
      <ScalarVariable name="f[2]" valueReference="12" description="Frequency 2 of it" causality="calculatedParameter"><Real unit="Hz"/></ScalarVariable>
      </ModelVariables></fmiModelDescription>"#;
    let table = variable_table(xml);
    let rows: Vec<&str> = table.lines().skip(3).collect();
    assert_eq!(
        rows,
        [
            "| `x` | 1 | input | Real, m | >= 0 | 2.068e11 | X & Y |",
            "| `m`, `m_index` | 2, 3 | parameter | Enumeration | `a`=1, `b`=2 | 1 | model (Integer twin: the same values as codes) |",
            "| `f[k]`, k = 1..2 | 11..12 | calculatedParameter | Real, Hz |  |  | Frequency k of it |",
        ]
    );
}
