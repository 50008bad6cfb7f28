//! Generated fragments: the files, the embedded blocks and their check.
//!
//! Every number in README.md and docs/ comes from a command a reader can rerun, and is
//! regenerated or checked when the code changes (a fragment written by an example, such as
//! `rod-feature-costs`, needs a test that recomputes what does not depend on the machine:
//! `tests/rod_feature_costs.rs`). A number produced by a program or a test lives in a
//! *generated fragment*: a Markdown file `docs/generated/<id>.md` (`<id>` lowercase letters,
//! digits and dashes, e.g. `report-front`), written by the program or test that measures it.
//! README.md and the Markdown files under docs/ embed a fragment between two whole lines,
//!
//! ```text
//! <!-- generated: <id> -->
//! ...the fragment's text, byte for byte...
//! <!-- end generated: <id> -->
//! ```
//!
//! and `tests/generated_fragments.rs` checks every embedded copy against its file (and that
//! every fragment is embedded somewhere). A test that measures numbers calls
//! [`check_generated`] with the Markdown it would write: it fails, showing which lines
//! differ, when the file is stale. `FLEXROD_BLESS=1` writes instead: the fragment files
//! (here) and the embedded copies (`FLEXROD_BLESS=1 cargo test --release --test
//! generated_fragments`). Edit the program or test that writes a fragment, never the
//! fragment or its embedded copy.

use std::path::{Path, PathBuf};

/// The repository root.
pub fn repository() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `docs/generated`, where the fragments live.
pub fn generated_dir() -> PathBuf {
    repository().join("docs").join("generated")
}

/// Whether `FLEXROD_BLESS` asks to write fragments instead of checking them (`1`).
pub fn blessing() -> bool {
    std::env::var_os("FLEXROD_BLESS").is_some_and(|v| v == "1")
}

/// A fragment id: lowercase ASCII letters and digits in dash-separated words (`report-front`).
pub fn is_fragment_id(id: &str) -> bool {
    !id.is_empty()
        && id.split('-').all(|w| {
            !w.is_empty()
                && w.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit())
        })
}

/// `docs/generated/<id>.md`.
pub fn fragment_path(id: &str) -> PathBuf {
    generated_dir().join(format!("{id}.md"))
}

/// The lines that differ between `old` and `new` (a longest-common-subsequence diff): `-` the
/// old line, `+` the new one, each with its 1-based line number; at most `limit` lines shown.
pub fn line_diff(old: &str, new: &str, limit: usize) -> String {
    let a: Vec<&str> = old.lines().collect();
    let b: Vec<&str> = new.lines().collect();
    // lcs[i][j]: length of the common subsequence of a[i..] and b[j..].
    let mut lcs = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for i in (0..a.len()).rev() {
        for j in (0..b.len()).rev() {
            lcs[i][j] = if a[i] == b[j] {
                lcs[i + 1][j + 1] + 1
            } else {
                lcs[i + 1][j].max(lcs[i][j + 1])
            };
        }
    }
    let mut out = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        if i < a.len() && j < b.len() && a[i] == b[j] {
            i += 1;
            j += 1;
        } else if i < a.len() && (j == b.len() || lcs[i + 1][j] >= lcs[i][j + 1]) {
            out.push(format!("-{:>4}: {}", i + 1, a[i]));
            i += 1;
        } else {
            out.push(format!("+{:>4}: {}", j + 1, b[j]));
            j += 1;
        }
    }
    if old.ends_with('\n') != new.ends_with('\n') {
        out.push("(the final newline differs)".to_string());
    }
    let total = out.len();
    if total > limit {
        out.truncate(limit);
        out.push(format!("... {} more differing lines", total - limit));
    }
    out.join("\n")
}

/// Check `markdown`, which a test has just generated, against `docs/generated/<id>.md`: fail
/// with the differing lines unless they are equal. With `FLEXROD_BLESS=1` write the file
/// instead (then bless `tests/generated_fragments.rs` to update the embedded copies). A
/// fragment is embedded as whole lines, so a final newline is added if `markdown` lacks one.
pub fn check_generated(id: &str, markdown: &str) {
    assert!(
        is_fragment_id(id),
        "'{id}' is not a fragment id (lowercase letters and digits, words joined by '-')"
    );
    let mut text = markdown.to_string();
    if !text.is_empty() && !text.ends_with('\n') {
        text.push('\n');
    }
    let path = fragment_path(id);
    let current = std::fs::read_to_string(&path).ok();
    if blessing() {
        if current.as_deref() != Some(text.as_str()) {
            std::fs::create_dir_all(generated_dir()).expect("create docs/generated");
            std::fs::write(&path, &text)
                .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
            eprintln!("blessed docs/generated/{id}.md");
        }
        return;
    }
    match current {
        None => panic!(
            "docs/generated/{id}.md does not exist: run with FLEXROD_BLESS=1 to write it, then embed \
             it between `<!-- generated: {id} -->` and `<!-- end generated: {id} -->`"
        ),
        Some(old) if old != text => panic!(
            "docs/generated/{id}.md is stale (- the file, + what this test measures now); \
             FLEXROD_BLESS=1 rewrites it:\n{}",
            line_diff(&old, &text, 40)
        ),
        Some(_) => {}
    }
}
