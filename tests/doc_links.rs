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
//! - The comments of the tests (`//` lines of tests/**/*.rs and fmu/tests/*.rs; `#` lines and
//!   triple-quoted strings of tests/python/**/*.py) name README.md and docs/ pages that exist:
//!   a page's section (`docs/fmu.md, "Time per call"`, `README.md, "Variables"`) begins a
//!   heading of that page, a fragment named by its id (the word fragment, then the id in
//!   backticks) is a file of docs/generated,
//!   and a page named before the fragment in its sentence, or in parentheses right after it,
//!   embeds it.

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

/// The headings of a Markdown text (outside fenced blocks), without the `#` marks.
fn headings(text: &str) -> Vec<String> {
    let mut out = Vec::new();
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
        if title.starts_with(' ') {
            out.push(title.trim().to_string());
        }
    }
    out
}

/// The comments of a test source, each run of comment lines joined into one text, with the
/// line it starts on. Rust: lines that start with `//` (`///` and `//!` too); Python: lines
/// that start with `#`, and triple-quoted strings (docstrings).
fn comments(text: &str, python: bool) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut block: Option<(usize, String)> = None;
    // An open triple-quoted string: its first line, its quotes, its text so far.
    let mut docstring: Option<(usize, &str, String)> = None;
    for (k, line) in text.lines().enumerate() {
        let number = k + 1;
        if let Some((start, quotes, mut doc)) = docstring.take() {
            let (piece, closed) = match line.find(quotes) {
                Some(end) => (&line[..end], true),
                None => (line, false),
            };
            if !piece.trim().is_empty() {
                doc.push(' ');
                doc.push_str(piece.trim());
            }
            if closed {
                out.push((start, doc));
            } else {
                docstring = Some((start, quotes, doc));
            }
            continue;
        }
        let trimmed = line.trim_start();
        let comment = if python {
            trimmed.strip_prefix('#')
        } else {
            trimmed
                .strip_prefix("//")
                .map(|c| c.trim_start_matches(['/', '!']))
        };
        if let Some(c) = comment {
            let b = block.get_or_insert_with(|| (number, String::new()));
            if !b.1.is_empty() {
                b.1.push(' ');
            }
            b.1.push_str(c.trim());
            continue;
        }
        out.extend(block.take());
        if python {
            for quotes in ["\"\"\"", "'''"] {
                if let Some(start) = line.find(quotes) {
                    let rest = &line[start + 3..];
                    match rest.find(quotes) {
                        Some(end) => out.push((number, rest[..end].trim().to_string())),
                        None => docstring = Some((number, quotes, rest.trim().to_string())),
                    }
                    break;
                }
            }
        }
    }
    out.extend(block.take());
    out.extend(docstring.map(|(start, _, doc)| (start, doc)));
    out
}

/// What a comment names: a README.md or docs/ page, or a fragment.
#[derive(Debug, PartialEq)]
enum Named {
    /// A page (relative to the repository root; `README` is README.md) at a byte offset of the
    /// sentence, with the section quoted after it (`docs/fmu.md, "Time per call"`).
    Page {
        at: usize,
        page: String,
        section: Option<String>,
    },
    /// A fragment named by its id in backticks after the word fragment, at a byte offset of
    /// the sentence; `end` is the offset after the id's closing backtick.
    Fragment { at: usize, end: usize, id: String },
}

/// The sentences of a comment: split after `.`, `!` or `?` followed by a space and a capital.
fn sentences(text: &str) -> Vec<&str> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut start = 0;
    for i in 0..b.len() {
        if matches!(b[i], b'.' | b'!' | b'?')
            && b.get(i + 1) == Some(&b' ')
            && b.get(i + 2).is_some_and(u8::is_ascii_uppercase)
        {
            out.push(&text[start..=i]);
            start = i + 2;
        }
    }
    out.push(&text[start..]);
    out
}

/// The pages and fragments a sentence names, in order.
fn named_in(sentence: &str) -> Vec<Named> {
    let b = sentence.as_bytes();
    let path_char = |c: u8| c.is_ascii_alphanumeric() || b"_./-#".contains(&c);
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let boundary = i == 0 || !(path_char(b[i - 1]) || b[i - 1] == b'$');
        let rest = &sentence[i..];
        let page = if !boundary {
            None
        } else if rest.starts_with("README.md") {
            Some(("README.md".to_string(), i + "README.md".len()))
        } else if rest.starts_with("README")
            && b.get(i + 6)
                .is_none_or(|&c| !(c.is_ascii_alphanumeric() || c == b'_'))
        {
            Some(("README.md".to_string(), i + "README".len()))
        } else if rest.starts_with("docs/") {
            let mut j = i + 5;
            while j < b.len() && path_char(b[j]) {
                j += 1;
            }
            let word = sentence[i..j].trim_end_matches('.');
            // `docs/generated/<id>.md`, `docs/figures/{name}.py`: patterns, not pages.
            (!matches!(b.get(j), Some(b'<' | b'{' | b'*')))
                .then(|| (word.to_string(), i + word.len()))
        } else {
            None
        };
        if let Some((page, end)) = page {
            let section = sentence[end..]
                .strip_prefix(',')
                .map(str::trim_start)
                .and_then(|a| a.strip_prefix('"'))
                .and_then(|a| a.find('"').map(|q| a[..q].to_string()));
            out.push(Named::Page {
                at: i,
                page,
                section,
            });
            i = end;
            continue;
        }
        if boundary && rest.starts_with("fragment `") {
            let id_start = i + "fragment `".len();
            if let Some(len) = sentence[id_start..].find('`') {
                out.push(Named::Fragment {
                    at: i,
                    end: id_start + len + 1,
                    id: sentence[id_start..id_start + len].to_string(),
                });
                i = id_start + len + 1;
                continue;
            }
        }
        i += 1;
    }
    out
}

/// Whether `section`, named in a comment, begins one of the headings of `page_text` (compared
/// in lower case, without backticks).
fn section_exists(page_text: &str, section: &str) -> bool {
    let plain = |s: &str| s.replace('`', "").to_lowercase();
    let section = plain(section);
    headings(page_text)
        .iter()
        .any(|h| plain(h).starts_with(&section))
}

/// What is wrong with the pages, sections and fragments a comment names.
fn comment_problems(text: &str) -> Vec<String> {
    let mut problems = Vec::new();
    for sentence in sentences(text) {
        let named = named_in(sentence);
        for (k, n) in named.iter().enumerate() {
            match n {
                Named::Page { page, section, .. } => {
                    let (file, anchor) = match page.split_once('#') {
                        Some((f, a)) => (f, Some(a)),
                        None => (page.as_str(), None),
                    };
                    let path = repository().join(file);
                    if !path.exists() {
                        problems.push(format!("{file} does not exist"));
                        continue;
                    }
                    if !file.ends_with(".md") {
                        continue;
                    }
                    let page_text = std::fs::read_to_string(&path).unwrap_or_default();
                    if anchor.is_some_and(|a| !anchors(&page_text).contains(a)) {
                        problems.push(format!("{page}: no heading with this anchor"));
                    }
                    if let Some(section) = section {
                        if !section_exists(&page_text, section) {
                            problems.push(format!("{file}, \"{section}\": no such heading"));
                        }
                    }
                }
                Named::Fragment { end, id, .. } => {
                    // Not an id (a file name pattern such as `docs/generated/<id>.md`).
                    if !common::is_fragment_id(id) {
                        continue;
                    }
                    if !common::fragment_path(id).is_file() {
                        problems.push(format!(
                            "fragment `{id}`: docs/generated/{id}.md does not exist"
                        ));
                        continue;
                    }
                    // The pages named before the fragment in its sentence, and the one in
                    // parentheses right after it, embed it.
                    let right_after = named.get(k + 1).filter(|m| {
                        matches!(m, Named::Page { at, .. } if sentence[*end..*at].trim() == "(")
                    });
                    let marker = format!("<!-- generated: {id} -->");
                    for m in named[..k].iter().chain(right_after) {
                        let Named::Page { page, .. } = m else {
                            continue;
                        };
                        let file = page.split('#').next().unwrap_or(page);
                        if !file.ends_with(".md") || file.starts_with("docs/generated/") {
                            continue;
                        }
                        let embeds = std::fs::read_to_string(repository().join(file))
                            .is_ok_and(|t| t.contains(&marker));
                        if !embeds {
                            problems.push(format!("{file} does not embed the fragment `{id}`"));
                        }
                    }
                }
            }
        }
    }
    problems
}

/// The test sources whose comments are checked: tests/**/*.rs (tests/python/**/*.py among
/// them) and fmu/tests/*.rs.
fn test_sources() -> Vec<PathBuf> {
    let mut files = files_under(&repository().join("tests"), &["rs", "py"]);
    files.extend(files_under(&repository().join("fmu/tests"), &["rs"]));
    files
}

#[test]
fn test_comments_name_pages_sections_and_fragments_that_exist() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for file in test_sources() {
        let name = relative(&file);
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        let python = file.extension().is_some_and(|e| e == "py");
        for (line, comment) in comments(&text, python) {
            checked += sentences(&comment)
                .iter()
                .map(|s| named_in(s).len())
                .sum::<usize>();
            for problem in comment_problems(&comment) {
                failures.push(format!("{name}:{line}: {problem}"));
            }
        }
    }
    println!("{checked} pages, sections and fragments named in test comments checked");
    assert!(
        checked > 50,
        "only {checked} references found in the test comments"
    );
    assert!(
        failures.is_empty(),
        "{} reference(s) in the tests' comments to what does not exist (name the docs/ page \
         and its heading that holds the text):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn test_comments_are_read_as_written() {
    let rust = "let x = 1; // not a comment line\n/// README, \"Dynamics\": the table\n\
                /// (generated fragment\n/// `dynamics-checks`).\nfn f() {}\n//! docs/fmu.md\n";
    assert_eq!(
        comments(rust, false),
        [
            (
                2,
                "README, \"Dynamics\": the table (generated fragment `dynamics-checks`)."
                    .to_string()
            ),
            (6, "docs/fmu.md".to_string()),
        ]
    );
    let python = "\"\"\"The model (docs/fmu.md,\n\"Time per call\").\"\"\"\nx = 1  # trailing\n\
                  # a README.md, \"Variables\" line\n";
    assert_eq!(
        comments(python, true),
        [
            (1, "The model (docs/fmu.md, \"Time per call\").".to_string()),
            (4, "a README.md, \"Variables\" line".to_string()),
        ]
    );
    let sentence =
        "See README, \"Scenes\", docs/usage.md. and the fragment `limits` (docs/robustness.md)";
    assert_eq!(
        named_in(sentence),
        [
            Named::Page {
                at: 4,
                page: "README.md".into(),
                section: Some("Scenes".into())
            },
            Named::Page {
                at: 22,
                page: "docs/usage.md".into(),
                section: None
            },
            Named::Fragment {
                at: 45,
                end: 62,
                id: "limits".into()
            },
            Named::Page {
                at: 64,
                page: "docs/robustness.md".into(),
                section: None
            },
        ]
    );
    assert_eq!(
        sentences("One e.g. two. Three docs/a.md. Four"),
        ["One e.g. two.", "Three docs/a.md.", "Four"]
    );
    // A README section that is not a heading, a fragment the page before it does not embed, a
    // fragment that does not exist; a page named after a fragment outside parentheses is not
    // held to it.
    let problems = comment_problems(
        "README, \"Dynamics\": a table (fragment `dynamics-checks`). The fragment \
         `no-such-fragment`. The fragment `limits` (docs/robustness.md, \"Limits\"), timed \
         in docs/performance.md.",
    );
    assert_eq!(
        problems,
        [
            "README.md, \"Dynamics\": no such heading",
            "README.md does not embed the fragment `dynamics-checks`",
            "fragment `no-such-fragment`: docs/generated/no-such-fragment.md does not exist",
        ]
    );
}

/// README.md opens with exactly two commands for a fresh machine (the first fenced block:
/// build the default scene's FMU and run it, run every test) and stays at most 250 lines.
#[test]
fn readme_opens_with_two_commands_and_stays_short() {
    let text = std::fs::read_to_string(repository().join("README.md")).expect("read README.md");
    let lines = text.lines().count();
    assert!(lines <= 250, "README.md has {lines} lines: at most 250");
    let (code, _) = code_and_links(&text);
    let first = code
        .iter()
        .find(|c| c.contains('\n'))
        .expect("README.md has a fenced block");
    let commands: Vec<&str> = first
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .collect();
    assert_eq!(
        commands,
        [
            "cargo run --release -p fmu -- --simulate",
            "bash tests/run_all.sh"
        ],
        "README.md's first block"
    );
}

/// Phrases that tell how the code came to be rather than what it is (matched in lower case,
/// at word boundaries). Plain "previous" and "used to" are not among them: "the previous step",
/// "the previous law", "used to check" say what is.
const HISTORY_PHRASES: &[&str] = &[
    "previous default",
    "previous version",
    "previously",
    "formerly",
    "used to be",
    "no longer",
    "not anymore",
    "anymore",
    "any longer",
    "before this change",
    "after this change",
    "until now",
    "until recently",
    "in earlier versions",
    "the old default",
    "the new default",
    "now defaults",
    "is now",
    "are now",
    "now uses",
    "was changed",
    "were changed",
    "has been changed",
    "have been changed",
    "was replaced",
    "were replaced",
    "has been replaced",
    "was renamed",
    "has been renamed",
    "was removed",
    "has been removed",
];

/// The history phrases in `text`: (byte offset, phrase).
fn history_phrases(text: &str) -> Vec<(usize, &'static str)> {
    let lower = text.to_lowercase();
    let b = lower.as_bytes();
    let word = |i: usize| b[i].is_ascii_alphanumeric() || b[i] == b'_';
    let mut hits = Vec::new();
    for phrase in HISTORY_PHRASES {
        for (at, _) in lower.match_indices(phrase) {
            let end = at + phrase.len();
            if (at == 0 || !word(at - 1)) && (end == b.len() || !word(end)) {
                hits.push((at, *phrase));
            }
        }
    }
    hits.sort();
    hits
}

#[test]
fn history_phrases_are_found() {
    let found = |t: &str| {
        history_phrases(t)
            .into_iter()
            .map(|(_, p)| p)
            .collect::<Vec<_>>()
    };
    assert_eq!(
        found("h 3e-4 (the Previous default); it Was Replaced, and is now faster."),
        ["previous default", "was replaced", "is now"]
    );
    for clean in [
        "the previous step's acceleration",
        "the value the previous law has",
        "used to check, never as a dependency",
        "thesis now", // "is now" inside a word
        "a nowhere-dense set",
    ] {
        assert!(found(clean).is_empty(), "{clean}: {:?}", found(clean));
    }
}

/// README.md and every Markdown file under docs/ (generated fragments and reports included)
/// say what is: none has a phrase of [`HISTORY_PHRASES`].
#[test]
fn readme_and_docs_say_what_is() {
    let mut files = vec![repository().join("README.md")];
    files.extend(files_under(&repository().join("docs"), &["md"]));
    let mut failures = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("read a Markdown file");
        for (at, phrase) in history_phrases(&text) {
            let line = text[..at].matches('\n').count() + 1;
            failures.push(format!("{}:{line}: \"{phrase}\"", relative(&file)));
        }
    }
    assert!(
        failures.is_empty(),
        "{} phrase(s) in README.md or docs/ that tell how something came to be (say what is; \
         a generated fragment: change the program or test that writes it):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// docs/README.md says no document there points outside the repository: no Markdown file
/// under docs/ has an http(s) address (a link, an autolink or a bare address).
#[test]
fn docs_point_nowhere_outside_the_repository() {
    let index =
        std::fs::read_to_string(repository().join("docs/README.md")).expect("read docs/README.md");
    assert!(
        index.contains("no document points outside the repository"),
        "docs/README.md no longer says so: remove this test or restore the statement"
    );
    let mut failures = Vec::new();
    for file in files_under(&repository().join("docs"), &["md"]) {
        let text = std::fs::read_to_string(&file).expect("read a Markdown file");
        for (at, _) in text.match_indices("http") {
            let rest = &text[at..];
            if rest.starts_with("http://") || rest.starts_with("https://") {
                let line = text[..at].matches('\n').count() + 1;
                let address: String = rest
                    .chars()
                    .take_while(|c| !c.is_whitespace() && *c != ')')
                    .collect();
                failures.push(format!("{}:{line}: {address}", relative(&file)));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "addresses outside the repository in docs/ (docs/README.md says there are none):\n{}",
        failures.join("\n")
    );
}
