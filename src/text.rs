//! Numbers, times and echoed input as messages print them, and the characters a text may hold
//! to reach modelDescription.xml.

/// Longest piece of input (a line of a scene or table, a key, a flag's value) a message
/// echoes, in characters: enough to recognise it, and an 800 KB line does not flood a log.
pub const ECHO_CHARS: usize = 200;

/// `x` as short exact text: the shortest text that reads back as `x`, plain between 1e-4 and
/// 1e9 (`0.0838`, `129`), else in e-notation (`1e-7`, `2.068e11`). Integer parameters print
/// through [`crate::error::ModelError::InvalidInteger`], as integers at any size.
pub fn number(x: f64) -> String {
    if x == 0.0 || (1e-4..1e9).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A time `t` (s) for a message: [`number`], the shortest text that reads back as `t`, at any
/// magnitude (`1e-7`, `1e-13`, `0.0838`), so that two different times never print alike (a
/// communication point `k dt` with round-off prints it: `0.0055000000000000005`).
pub fn time(t: f64) -> String {
    number(t)
}

/// `text` as a message echoes it: unchanged up to [`ECHO_CHARS`] characters, else its first
/// [`ECHO_CHARS`] characters followed by `... (N bytes)`.
pub fn echo(text: &str) -> String {
    match text.char_indices().nth(ECHO_CHARS) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}... ({} bytes)", &text[..cut], text.len()),
    }
}

/// Every line of `message` cut as [`echo`] cuts a text: for messages of other libraries
/// that quote their input (a TOML parser's error shows the offending line).
pub fn echo_lines(message: &str) -> String {
    message.lines().map(echo).collect::<Vec<_>>().join("\n")
}

/// The first character of `text` that modelDescription.xml cannot carry unchanged in an
/// attribute value, with its position (in characters, from 1): XML 1.0 has no control
/// character but tab, line feed and carriage return, and an attribute turns those into spaces;
/// U+FFFE and U+FFFF are not XML characters.
pub fn first_non_xml_char(text: &str) -> Option<(usize, char)> {
    text.chars()
        .enumerate()
        .find(|&(_, c)| c < ' ' || c == '\u{FFFE}' || c == '\u{FFFF}')
        .map(|(i, c)| (i + 1, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_times_print_exactly() {
        assert_eq!(number(129.0), "129");
        assert_eq!(number(1e9), "1e9");
        assert_eq!(number(0.0838), "0.0838");
        assert_eq!(number(2.068e11), "2.068e11");
        assert_eq!(number(1e-20), "1e-20");
        assert_eq!(number(5e-324), "5e-324");
        assert_eq!(time(1e-7), "1e-7");
        assert_eq!(time(55.0 * 1e-4), "0.0055000000000000005");
        assert_eq!(time(0.0055), "0.0055");
        assert_eq!(time(1e-13), "1e-13");
        assert_eq!(time(0.0), "0");
    }

    #[test]
    fn echoes_are_bounded() {
        assert_eq!(echo("short"), "short");
        let long = "[".repeat(800_000);
        let cut = echo(&long);
        assert!(
            cut.ends_with("... (800000 bytes)"),
            "{}",
            &cut[cut.len() - 30..]
        );
        assert!(cut.len() < ECHO_CHARS + 30);
        assert_eq!(echo_lines(&format!("a\n{long}\nb")).lines().count(), 3);
    }

    #[test]
    fn control_characters_are_found() {
        assert_eq!(first_non_xml_char("ab<&>\"'é"), None);
        assert_eq!(first_non_xml_char("ab\u{1}c"), Some((3, '\u{1}')));
        assert_eq!(first_non_xml_char("a\nb"), Some((2, '\n')));
    }
}
