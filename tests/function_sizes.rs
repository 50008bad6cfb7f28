//! No function in `src/` is longer than [`MAX_LINES`] lines: every `fn` item of every `.rs`
//! file under `src/` (free functions, methods, trait methods with a body, functions nested in
//! other functions, test functions), measured from the line of its `fn` keyword to the line of
//! its body's closing brace, both included. The test fails naming every longer function with
//! its file, line and length; a long function is split by what it does.
//!
//! The scan reads the source as text: comments, string literals (raw and byte strings too) and
//! character literals are blanked first, so that braces and the word `fn` in them do not count;
//! a function's body is the first `{` after its name outside parentheses and brackets (a `;`
//! there first: a declaration without a body, not measured), up to its matching `}`.

use std::path::{Path, PathBuf};

/// The longest a function may be, in lines.
const MAX_LINES: usize = 150;

/// Functions allowed over [`MAX_LINES`]: (file under the repository root, function name).
/// None; the test fails when an entry is within the limit, so the list only shrinks.
const ALLOWED: &[(&str, &str)] = &[];

/// One `fn` item: its name, the line of its `fn` keyword (1-based) and its length in lines.
#[derive(Debug)]
struct Function {
    name: String,
    line: usize,
    lines: usize,
}

/// `text` with comments, string literals and character literals replaced by spaces (line
/// breaks kept, so that line numbers stay), as characters.
fn blank_non_code(text: &str) -> Vec<char> {
    let c: Vec<char> = text.chars().collect();
    let mut out = c.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for ch in &mut out[from..to] {
            if *ch != '\n' {
                *ch = ' ';
            }
        }
    };
    let is_ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    while i < c.len() {
        let next = |k: usize| c.get(i + k).copied().unwrap_or('\0');
        if c[i] == '/' && next(1) == '/' {
            let end = (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len());
            blank(&mut out, i, end);
            i = end;
        } else if c[i] == '/' && next(1) == '*' {
            // Block comments nest.
            let (mut depth, mut j) = (0usize, i);
            while j < c.len() {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    j += 1;
                }
            }
            blank(&mut out, i, j.min(c.len()));
            i = j;
        } else if (c[i] == 'r' || (c[i] == 'b' && next(1) == 'r'))
            && (i == 0 || !is_ident(c[i - 1]))
            && {
                let start = if c[i] == 'b' { i + 2 } else { i + 1 };
                let hashes = c[start..].iter().take_while(|&&ch| ch == '#').count();
                c.get(start + hashes) == Some(&'"')
            }
        {
            // Raw string: r"...", r#"..."#, br"...".
            let start = if c[i] == 'b' { i + 2 } else { i + 1 };
            let hashes = c[start..].iter().take_while(|&&ch| ch == '#').count();
            let mut j = start + hashes + 1;
            while j < c.len() {
                if c[j] == '"'
                    && c[j + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&h| h == '#')
                        .count()
                        == hashes
                {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            blank(&mut out, i, j.min(c.len()));
            i = j;
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, (j + 1).min(c.len()));
            i = j + 1;
        } else if c[i] == '\'' {
            // A character literal ('a', '\n', '\u{..}', '\''), not a lifetime ('a).
            let end = if next(1) == '\\' {
                (i + 2..c.len().min(i + 12)).find(|&j| c[j] == '\'' && j > i + 2)
            } else if next(2) == '\'' {
                Some(i + 2)
            } else {
                None
            };
            match end {
                Some(end) => {
                    blank(&mut out, i, end + 1);
                    i = end + 1;
                }
                None => i += 1,
            }
        } else {
            i += 1;
        }
    }
    out
}

/// Every `fn` item with a body in `text`.
fn functions(text: &str) -> Vec<Function> {
    let code = blank_non_code(text);
    let is_ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let line_of = |at: usize| 1 + code[..at].iter().filter(|&&ch| ch == '\n').count();
    let mut found = Vec::new();
    for i in 0..code.len().saturating_sub(2) {
        let keyword = code[i] == 'f'
            && code[i + 1] == 'n'
            && code[i + 2].is_whitespace()
            && (i == 0 || !is_ident(code[i - 1]));
        if !keyword {
            continue;
        }
        let mut j = i + 2;
        while j < code.len() && code[j].is_whitespace() {
            j += 1;
        }
        let name: String = code[j..].iter().take_while(|&&ch| is_ident(ch)).collect();
        if name.is_empty() {
            continue;
        }
        // The body: the first `{` outside parentheses and brackets, unless a `;` comes first.
        let mut depth = 0i32;
        let mut open = None;
        for (k, &ch) in code.iter().enumerate().skip(j + name.len()) {
            match ch {
                '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                ';' if depth == 0 => break,
                '{' if depth == 0 => {
                    open = Some(k);
                    break;
                }
                _ => {}
            }
        }
        let Some(open) = open else {
            continue;
        };
        let mut braces = 0i32;
        let mut close = code.len() - 1;
        for (k, &ch) in code.iter().enumerate().skip(open) {
            match ch {
                '{' => braces += 1,
                '}' => {
                    braces -= 1;
                    if braces == 0 {
                        close = k;
                        break;
                    }
                }
                _ => {}
            }
        }
        let line = line_of(i);
        found.push(Function {
            name,
            line,
            lines: line_of(close) - line + 1,
        });
    }
    found
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_function_is_longer_than_the_limit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    files.sort();
    let mut too_long = Vec::new();
    let mut allowed_seen = Vec::new();
    for file in &files {
        let relative = file
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(file).unwrap();
        for f in functions(&text).into_iter().filter(|f| f.lines > MAX_LINES) {
            if ALLOWED.contains(&(relative.as_str(), f.name.as_str())) {
                allowed_seen.push((relative.clone(), f.name.clone()));
            } else {
                too_long.push(format!(
                    "{relative}:{} fn {} ({} lines)",
                    f.line, f.name, f.lines
                ));
            }
        }
    }
    assert!(
        too_long.is_empty(),
        "functions longer than {MAX_LINES} lines (split each by what it does):\n  {}",
        too_long.join("\n  ")
    );
    let stale: Vec<_> = ALLOWED
        .iter()
        .filter(|(file, name)| !allowed_seen.iter().any(|(f, n)| f == file && n == name))
        .collect();
    assert!(
        stale.is_empty(),
        "allowed long functions that are no longer over {MAX_LINES} lines (remove them from ALLOWED): {stale:?}"
    );
}

/// The scan's own cases: what counts as a function and as its length.
#[test]
fn the_scan_measures_functions_and_skips_non_code() {
    let text = r##"
/// fn in_a_doc_comment() {
fn outer(x: [f64; 3]) -> usize {
    let s = "fn in_a_string() { {";
    let r = r#"fn in_a_raw_string() }"#;
    let c = '{';
    let e = '\'';
    fn nested<'a>(y: &'a str) -> &'a str {
        y
    }
    /* fn in_a_block_comment() { /* nested */ } */
    let f: fn(usize) -> usize = |z| z;
    x.len()
}
trait T {
    fn declared(&self);
    fn with_default(&self) -> u8 where Self: Sized { 0 }
}
"##;
    let found: Vec<(String, usize, usize)> = functions(text)
        .into_iter()
        .map(|f| (f.name, f.line, f.lines))
        .collect();
    assert_eq!(
        found,
        vec![
            ("outer".to_string(), 3, 12),
            ("nested".to_string(), 8, 3),
            ("with_default".to_string(), 17, 1),
        ]
    );
}
