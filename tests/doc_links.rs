//! README.md and docs/ name only what exists, and say what is, not how it came to be.
//!
//! - Every repository path named in README.md or a Markdown file under docs/ (a word in a code
//!   span or a fenced block that starts with `src/`, `tests/`, `examples/`, `docs/`, `scenes/`,
//!   `python/`, `benches/`, `fmu/` or `modelDescription/`, relative to the repository root; the
//!   target of a Markdown link, relative to the file) exists; a link's `#anchor` names a heading
//!   of the Markdown file it points to. Words with placeholders (`<name>`, `*`, `{a,b}`, `...`)
//!   are patterns, not paths, and are skipped.
//! - No text file of README.md and docs/ (Markdown, and the SVG, XML, CSV and Python files there)
//!   refers to the development history: "issue N", "session", "commit <hash>", seed file names
//!   ("seed 000", `000_<16 hex>`) or `../shared`. Hits in files written by programs and tests
//!   outside this test's reach are listed in [`KNOWN_HITS`] with the command that rewrites them;
//!   the test also fails when such a listed hit is gone, so the list only shrinks.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::repository;

/// Prefixes of the repository paths the documents name.
const ROOTS: &[&str] = &[
    "src/",
    "tests/",
    "examples/",
    "docs/",
    "scenes/",
    "python/",
    "benches/",
    "fmu/",
    "modelDescription/",
];

/// History references in generated files this test cannot fix: (file, the hit's text). Each
/// goes when the program or test that writes the file stops writing it and the file is
/// regenerated:
/// - docs/report/*, docs/generated/report-*: `cargo run --release --bin report` (its text is in
///   src/bin/report);
/// - docs/generated/extreme-cases.md: `FLEXROD_BLESS=1 cargo test --release --test extreme`;
/// - docs/generated/fuzz-long.md: the long mode of tests/fuzz_fmi.rs (about an hour on 2 threads).
const KNOWN_HITS: &[(&str, &str)] = &[];

/// Files under `dir` (recursively) whose extension is one of `extensions`, sorted.
fn files_under(dir: &Path, extensions: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| extensions.contains(&e))
            {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// README.md and every Markdown file under docs/.
fn markdown_files() -> Vec<PathBuf> {
    let mut files = vec![repository().join("README.md")];
    files.extend(files_under(&repository().join("docs"), &["md"]));
    files
}

fn relative(path: &Path) -> String {
    path.strip_prefix(repository())
        .unwrap_or(path)
        .display()
        .to_string()
}

/// The code spans and fenced code blocks of a Markdown text, and its link targets. Code spans
/// and links may continue over the lines of a paragraph.
fn code_and_links(text: &str) -> (Vec<String>, Vec<String>) {
    let mut code = Vec::new();
    let mut links = Vec::new();
    let mut fence: Option<String> = None;
    let mut paragraph = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let trimmed = line.trim_start();
        let is_fence = trimmed.starts_with("```") || trimmed.starts_with("~~~");
        if fence.is_none() && !is_fence && !line.trim().is_empty() {
            paragraph.push_str(line);
            paragraph.push('\n');
            if lines.peek().is_some() {
                continue;
            }
        }
        if !paragraph.is_empty() {
            spans_and_links(&paragraph, &mut code, &mut links);
            paragraph.clear();
        }
        if is_fence {
            fence = match fence {
                Some(block) => {
                    code.push(block);
                    None
                }
                None => Some(String::new()),
            };
        } else if let Some(block) = fence.as_mut() {
            block.push_str(line);
            block.push('\n');
        }
    }
    (code, links)
}

/// The code spans (text between matching runs of backticks) of a paragraph, and the targets of
/// its links and images (`](target)`) outside them.
fn spans_and_links(paragraph: &str, code: &mut Vec<String>, links: &mut Vec<String>) {
    let mut rest = paragraph;
    let mut prose = String::new();
    while let Some(start) = rest.find('`') {
        prose.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let after = &rest[start + ticks..];
        let closing = "`".repeat(ticks);
        match after.find(&closing) {
            Some(end) => {
                code.push(after[..end].to_string());
                rest = &after[end + ticks..];
            }
            None => rest = after,
        }
    }
    prose.push_str(rest);
    let mut p = prose.as_str();
    while let Some(k) = p.find("](") {
        let after = &p[k + 2..];
        match after.find(')') {
            Some(end) => {
                links.push(after[..end].trim().to_string());
                p = &after[end + 1..];
            }
            None => break,
        }
    }
}

/// The repository paths named in code: words starting with one of [`ROOTS`], without
/// surrounding punctuation; patterns with placeholders are left out.
fn named_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    for word in code.split(|c: char| c.is_whitespace() || "'\"=,;()[]".contains(c)) {
        let word = word.trim_end_matches(['.', ':', '`']);
        if !ROOTS.iter().any(|r| word.starts_with(r)) {
            continue;
        }
        if word.contains(['<', '>', '*', '{', '}', '$', '|', '…']) || word.contains("...") {
            continue;
        }
        // `src/fmi/ffi/fmi3/` or `src/fmi/mod.rs:123`
        let word = word.split(':').next().unwrap_or(word);
        out.push(word.to_string());
    }
    out
}

/// GitHub's anchors of a Markdown text's headings (lowercase, spaces to dashes, punctuation
/// other than `-` and `_` dropped; repeated headings get `-1`, `-2`, ...).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut in_fence = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence || !line.starts_with('#') {
            continue;
        }
        let title = line.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                _ => None,
            })
            .collect();
        let mut candidate = slug.clone();
        let mut k = 0;
        while seen.contains(&candidate) {
            k += 1;
            candidate = format!("{slug}-{k}");
        }
        seen.insert(candidate);
    }
    seen
}

#[test]
fn named_paths_and_links_exist() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for file in markdown_files() {
        let name = relative(&file);
        let text = std::fs::read_to_string(&file).expect("read a Markdown file");
        let (code, links) = code_and_links(&text);
        for path in code.iter().flat_map(|c| named_paths(c)) {
            checked += 1;
            if !repository().join(&path).exists() {
                failures.push(format!("{name}: `{path}` does not exist"));
            }
        }
        for link in links {
            let link = link.split_whitespace().next().unwrap_or("").to_string();
            if link.is_empty()
                || link.starts_with("http://")
                || link.starts_with("https://")
                || link.starts_with("mailto:")
            {
                continue;
            }
            checked += 1;
            let (target, anchor) = match link.split_once('#') {
                Some((t, a)) => (t, Some(a)),
                None => (link.as_str(), None),
            };
            let target_path = if target.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(target)
            };
            if !target_path.exists() {
                failures.push(format!("{name}: link ({link}) points to nothing"));
                continue;
            }
            if let Some(anchor) = anchor {
                if target_path.extension().is_some_and(|e| e == "md") {
                    let target_text = std::fs::read_to_string(&target_path).unwrap_or_default();
                    if !anchors(&target_text).contains(anchor) {
                        failures.push(format!(
                            "{name}: link ({link}): no heading with the anchor #{anchor}"
                        ));
                    }
                }
            }
        }
    }
    println!("{checked} paths and links checked");
    assert!(checked > 100, "only {checked} paths and links found");
    assert!(
        failures.is_empty(),
        "{} broken path(s) or link(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The history references in `text`: (byte offset, the matched text). The patterns:
/// `\b[Ii]ssues? #?[0-9]+`, `\bsession\b`, `\bcommit [0-9a-f]{7,}\b`, `[Ss]eeds? ?0?0[0-2]`,
/// `00[0-2]_[0-9a-f]{16}`, `\.\./shared`.
fn history_hits(text: &str) -> Vec<(usize, String)> {
    let b = text.as_bytes();
    let word = |i: usize| i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_');
    let at = |i: usize, s: &str| b.len() >= i + s.len() && &b[i..i + s.len()] == s.as_bytes();
    let hex = |i: usize| i < b.len() && matches!(b[i], b'0'..=b'9' | b'a'..=b'f');
    let mut hits = Vec::new();
    for i in 0..b.len() {
        let boundary = i == 0 || !word(i - 1);
        let end: Option<usize> = (|| {
            if boundary && (at(i, "issue") || at(i, "Issue")) {
                let mut j = i + 5;
                if at(j, "s") {
                    j += 1;
                }
                if !at(j, " ") {
                    return None;
                }
                j += 1;
                if at(j, "#") {
                    j += 1;
                }
                let start = j;
                while j < b.len() && b[j].is_ascii_digit() {
                    j += 1;
                }
                return (j > start).then_some(j);
            }
            if boundary && at(i, "session") && !word(i + 7) {
                return Some(i + 7);
            }
            if boundary && at(i, "commit ") {
                let mut j = i + 7;
                while hex(j) {
                    j += 1;
                }
                return (j - (i + 7) >= 7 && !word(j)).then_some(j);
            }
            if at(i, "seed") || at(i, "Seed") {
                let mut j = i + 4;
                if at(j, "s") {
                    j += 1;
                }
                if at(j, " ") {
                    j += 1;
                }
                // 0?0[0-2]
                for skip in [1usize, 0] {
                    let k = j + skip;
                    if (skip == 0 || at(j, "0"))
                        && at(k, "0")
                        && k + 1 < b.len()
                        && matches!(b[k + 1], b'0'..=b'2')
                    {
                        return Some(k + 2);
                    }
                }
                return None;
            }
            if at(i, "00") && i + 3 < b.len() && matches!(b[i + 2], b'0'..=b'2') && b[i + 3] == b'_'
            {
                let j = i + 4;
                return (j + 16 <= b.len() && (j..j + 16).all(hex)).then_some(j + 16);
            }
            if at(i, "../shared") {
                return Some(i + 9);
            }
            None
        })();
        if let Some(end) = end {
            hits.push((i, String::from_utf8_lossy(&b[i..end]).into_owned()));
        }
    }
    hits
}

#[test]
fn history_patterns_are_found() {
    let found = |t: &str| {
        history_hits(t)
            .into_iter()
            .map(|(_, s)| s)
            .collect::<Vec<_>>()
    };
    assert_eq!(
        // The history words are spelled in pieces so that this file does not itself read as
        // history to a grep over the tree.
        found(concat!(
            "(iss",
            "ue 14) Iss",
            "ues #3 a session, at commit 6fc5bd2. seed 001, Seeds 000, seed000_x"
        )),
        [
            concat!("iss", "ue 14"),
            concat!("Iss", "ues #3"),
            "session",
            "commit 6fc5bd2",
            "seed 001",
            "Seeds 000",
            "seed000"
        ]
    );
    assert_eq!(
        found("`001_300b657b5809bf4a.txt`, ../shared/design"),
        ["001_300b657b5809bf4a", "../shared"]
    );
    for clean in [
        concat!("tiss", "ue 1"),
        "issue of 3",
        "sessions",
        "commit abc",
        "commit 6fc5bd2x",
        "seeds 0 to 5999",
        "seed (K)",
        "1000_x",
        "a shared file",
    ] {
        assert!(found(clean).is_empty(), "{clean}: {:?}", found(clean));
    }
}

#[test]
fn readme_and_docs_do_not_refer_to_the_development_history() {
    let mut files = vec![repository().join("README.md")];
    files.extend(files_under(
        &repository().join("docs"),
        &["md", "svg", "xml", "csv", "py", "toml", "txt"],
    ));
    let mut failures = Vec::new();
    let mut known_seen = BTreeSet::new();
    for file in files {
        let name = relative(&file);
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue; // not text
        };
        for (offset, hit) in history_hits(&text) {
            if KNOWN_HITS.contains(&(name.as_str(), hit.as_str())) {
                known_seen.insert((name.clone(), hit));
                continue;
            }
            let line = text[..offset].matches('\n').count() + 1;
            failures.push(format!("{name}:{line}: \"{hit}\""));
        }
    }
    for (file, hit) in KNOWN_HITS {
        if !known_seen.contains(&(file.to_string(), hit.to_string())) {
            failures.push(format!(
                "{file}: the listed hit \"{hit}\" is gone: remove it from KNOWN_HITS"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} reference(s) to the development history in README.md or docs/ (say what is, cite \
         papers by author and year):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn paths_links_and_anchors_are_read_as_written() {
    let text = "A `cargo run --example x -- --out docs/sweeps/a` and `src/fmi/ffi/`,\n\
                a span over `two\nlines src/lib.rs` and [a link](physics.md#the-mechanism).\n\
                \n```sh\n.venv/bin/python docs/figures/x.py [SCENE]\n```\n\
                `scenes/agrawal_shabana_<reference>.toml`, `tests/*.rs`, `src/main.rs:12`.\n";
    let (code, links) = code_and_links(text);
    let paths: Vec<String> = code.iter().flat_map(|c| named_paths(c)).collect();
    assert_eq!(
        paths,
        [
            "docs/sweeps/a",
            "src/fmi/ffi/",
            "src/lib.rs",
            "docs/figures/x.py",
            "src/main.rs"
        ]
    );
    assert_eq!(links, ["physics.md#the-mechanism"]);
    let headings =
        anchors("# A title\n## Mass matrix (`src/rod/ffr/rod.rs`)\n## A title\n```\n# no\n```\n");
    assert_eq!(
        headings.into_iter().collect::<Vec<_>>(),
        ["a-title", "a-title-1", "mass-matrix-srcrodffrrodrs"]
    );
}

#[test]
fn readme_scene_examples_are_scenes_that_build() {
    let text = std::fs::read_to_string(repository().join("README.md")).expect("read README.md");
    let mut scenes = 0;
    let mut block: Option<String> = None;
    for line in text.lines() {
        match (&mut block, line.trim_start()) {
            (None, "```toml") => block = Some(String::new()),
            (Some(b), "```") => {
                // A complete scene names its FMU; partial examples do not.
                if b.lines().any(|l| l.starts_with("name =")) {
                    let scene = flexrod::Scene::from_toml_str(b, "README.md")
                        .unwrap_or_else(|e| panic!("README.md's scene does not parse: {e}"));
                    flexrod::Simulation::new(&scene)
                        .unwrap_or_else(|e| panic!("README.md's scene does not build: {e}"));
                    scenes += 1;
                }
                block = None;
            }
            (Some(b), _) => {
                b.push_str(line);
                b.push('\n');
            }
            (None, _) => {}
        }
    }
    assert!(scenes >= 1, "README.md shows no complete scene");
}
