//! Messages to the importer's logger, filtered by the declared log categories.
//!
//! Rules:
//! - `fmi2Error` and `fmi2Fatal` messages are always passed on: they explain a failed call.
//! - Warnings and discards go to `logStatusWarning` / `logStatusDiscard`, on unless the
//!   importer switches them off with `fmi2SetDebugLogging`.
//! - Informational messages go to `logEvents`, on only with debug logging (`loggingOn` of
//!   `fmi2Instantiate`, or `fmi2SetDebugLogging`).
//!
//! The sink (the C callback) lives in `ffi.rs`; this module is safe Rust.

use std::borrow::Cow;

use super::status::{FmiError, Status};

/// The log categories declared in modelDescription.xml: (name, description).
pub const LOG_CATEGORIES: [(&str, &str); 6] = [
    (
        "logEvents",
        "Informational messages: initialization, resources, ignored settings",
    ),
    (
        "logStatusWarning",
        "Messages of calls that return fmi2Warning",
    ),
    (
        "logStatusDiscard",
        "Messages of calls that return fmi2Discard (a step that could not be completed)",
    ),
    (
        "logStatusError",
        "Messages of calls that return fmi2Error (always logged)",
    ),
    (
        "logStatusFatal",
        "Messages of calls that return fmi2Fatal (always logged)",
    ),
    ("logAll", "All of the above"),
];

const EVENTS: usize = 0;
const WARNING: usize = 1;
const DISCARD: usize = 2;
const ERROR: usize = 3;
const FATAL: usize = 4;
const ALL: usize = 5;

/// Where messages go: the importer's logger callback.
pub trait LogSink {
    /// Pass one message on. `message` is plain text (not a printf format).
    fn emit(&self, status: Status, category: &'static str, message: &str);
}

/// A logger that forwards to a sink according to the enabled categories.
pub struct Logger {
    sink: Option<Box<dyn LogSink>>,
    /// Enabled flags, indexed like [`LOG_CATEGORIES`] (without `logAll`).
    enabled: [bool; 5],
    /// The flags given at `fmi2Instantiate`, restored by `fmi2Reset`.
    initial: [bool; 5],
}

impl Logger {
    /// `logging_on` is `loggingOn` of `fmi2Instantiate`: it switches `logEvents` on.
    pub fn new(sink: Option<Box<dyn LogSink>>, logging_on: bool) -> Logger {
        let enabled = [logging_on, true, true, true, true];
        Logger {
            sink,
            enabled,
            initial: enabled,
        }
    }

    /// `fmi2Reset`: back to the settings of `fmi2Instantiate`.
    pub fn reset(&mut self) {
        self.enabled = self.initial;
    }

    /// A logger that drops everything (for tools and tests).
    pub fn silent() -> Logger {
        Logger::new(None, false)
    }

    /// `fmi2SetDebugLogging`: with no categories, all of them are switched to `on`;
    /// otherwise only the named ones. Unknown names are rejected and nothing changes.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> Result<(), FmiError> {
        let mut enabled = self.enabled;
        if categories.is_empty() {
            enabled = [on; 5];
        }
        for name in categories {
            match LOG_CATEGORIES.iter().position(|(n, _)| n == name) {
                Some(ALL) => enabled = [on; 5],
                Some(i) => enabled[i] = on,
                None => {
                    let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
                    return Err(FmiError::rejected(format!(
                        "unknown log category \"{name}\": allowed {}",
                        known.join(", ")
                    )));
                }
            }
        }
        self.enabled = enabled;
        Ok(())
    }

    /// Is debug logging of informational messages on? (Lets callers skip formatting.)
    pub fn events_on(&self) -> bool {
        self.sink.is_some() && self.enabled[EVENTS]
    }

    /// An informational message (category `logEvents`).
    pub fn event(&self, message: &str) {
        if self.events_on() {
            self.emit(Status::Ok, EVENTS, message);
        }
    }

    /// A message that explains the status of a call.
    pub fn status(&self, status: Status, message: &str) {
        let (category, always) = match status {
            Status::Ok | Status::Pending => (EVENTS, false),
            Status::Warning => (WARNING, false),
            Status::Discard => (DISCARD, false),
            Status::Error => (ERROR, true),
            Status::Fatal => (FATAL, true),
        };
        if always || self.enabled[category] {
            self.emit(status, category, message);
        }
    }

    fn emit(&self, status: Status, category: usize, message: &str) {
        if let Some(sink) = &self.sink {
            sink.emit(status, LOG_CATEGORIES[category].0, message);
        }
    }
}

/// The logger callback takes a printf format: escape `%` so the text is printed as is.
pub fn printf_escape(message: &str) -> Cow<'_, str> {
    if message.contains('%') {
        Cow::Owned(message.replace('%', "%%"))
    } else {
        Cow::Borrowed(message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;
    use std::rc::Rc;

    type Seen = Rc<RefCell<Vec<(Status, &'static str, String)>>>;
    struct Capture(Seen);
    impl LogSink for Capture {
        fn emit(&self, status: Status, category: &'static str, message: &str) {
            self.0
                .borrow_mut()
                .push((status, category, message.to_string()));
        }
    }

    #[test]
    fn errors_always_events_only_when_on() {
        let seen = Rc::new(RefCell::new(Vec::new()));
        let mut log = Logger::new(Some(Box::new(Capture(seen.clone()))), false);
        log.event("hidden");
        log.status(Status::Error, "shown");
        log.set_debug_logging(false, &[]).unwrap();
        log.status(Status::Warning, "hidden too");
        log.status(Status::Error, "still shown");
        log.set_debug_logging(true, &["logEvents"]).unwrap();
        log.event("now shown");
        let seen = seen.borrow();
        let texts: Vec<&str> = seen.iter().map(|(_, _, m)| m.as_str()).collect();
        assert_eq!(texts, ["shown", "still shown", "now shown"]);
        assert_eq!(seen[0].1, "logStatusError");
        assert_eq!(seen[2].1, "logEvents");
    }

    #[test]
    fn unknown_category_rejected_and_nothing_changes() {
        let mut log = Logger::new(None, false);
        let e = log
            .set_debug_logging(true, &["logEvents", "logNonsense"])
            .unwrap_err();
        assert!(e.message.contains("logNonsense"));
        assert!(!log.enabled[EVENTS]);
    }

    #[test]
    fn reset_restores_the_instantiation_settings() {
        let mut log = Logger::new(None, true);
        log.set_debug_logging(false, &[]).unwrap();
        assert!(!log.enabled[EVENTS] && !log.enabled[WARNING]);
        log.reset();
        assert_eq!(log.enabled, [true; 5]);
    }

    #[test]
    fn percent_is_escaped() {
        assert_eq!(printf_escape("50% of %s"), "50%% of %%s");
        assert!(matches!(printf_escape("plain"), Cow::Borrowed(_)));
    }
}
