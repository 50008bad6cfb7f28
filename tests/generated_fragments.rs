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
