//! FMI 2.0 status codes and the error type of the safe layer.
//!
//! The safe layer returns `Result<Status, FmiError>`: `Ok(Status::Ok | Status::Warning)` on
//! success, `Err` with `Status::Discard` or `Status::Error` and a message otherwise. The C
//! boundary (`ffi.rs`) logs the message and folds the result into the `fmi2Status` it returns.

use std::fmt;

/// `fmi2Status`, with the numeric values of `fmi2FunctionTypes.h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[repr(i32)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
    Pending = 5,
}

impl Status {
    /// The value returned through the C ABI.
    pub fn code(self) -> i32 {
        self as i32
    }

    /// Decode a status written by this layer (used by serialized FMU states).
    pub fn from_code(code: i32) -> Option<Status> {
        [
            Status::Ok,
            Status::Warning,
            Status::Discard,
            Status::Error,
            Status::Fatal,
            Status::Pending,
        ]
        .into_iter()
        .find(|s| s.code() == code)
    }
}

/// `fmi2StatusKind`: what `fmi2Get*Status` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StatusKind {
    DoStepStatus,
    PendingStatus,
    LastSuccessfulTime,
    Terminated,
}

impl StatusKind {
    /// Decode the C value; unknown values give an error naming the allowed ones.
    pub fn from_code(code: i32) -> Result<StatusKind, FmiError> {
        match code {
            0 => Ok(StatusKind::DoStepStatus),
            1 => Ok(StatusKind::PendingStatus),
            2 => Ok(StatusKind::LastSuccessfulTime),
            3 => Ok(StatusKind::Terminated),
            _ => Err(FmiError::rejected(format!(
                "status kind {code} is not an fmi2StatusKind: allowed 0 (fmi2DoStepStatus), 1 (fmi2PendingStatus), 2 (fmi2LastSuccessfulTime), 3 (fmi2Terminated)"
            ))),
        }
    }

    /// The C name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            StatusKind::DoStepStatus => "fmi2DoStepStatus",
            StatusKind::PendingStatus => "fmi2PendingStatus",
            StatusKind::LastSuccessfulTime => "fmi2LastSuccessfulTime",
            StatusKind::Terminated => "fmi2Terminated",
        }
    }
}

/// A failed FMI call: the status to return and the message for the importer's logger.
#[derive(Clone, Debug, PartialEq)]
pub struct FmiError {
    /// `Discard` or `Error`.
    pub status: Status,
    /// What went wrong, naming the offending value and its allowed range.
    pub message: String,
    /// True if the instance can no longer continue (it enters the FMI `Error` state);
    /// false if the call was rejected before anything changed (the instance is unchanged).
    pub instance_failed: bool,
}

impl FmiError {
    /// The call was rejected before it changed anything: the instance is unchanged and usable.
    pub fn rejected(message: impl Into<String>) -> FmiError {
        FmiError {
            status: Status::Error,
            message: message.into(),
            instance_failed: false,
        }
    }

    /// The instance cannot continue: it enters the `Error` state (only `fmi2Reset`,
    /// `fmi2SetFMUstate`, `fmi2FreeInstance` and the getters remain allowed).
    pub fn failed(message: impl Into<String>) -> FmiError {
        FmiError {
            status: Status::Error,
            message: message.into(),
            instance_failed: true,
        }
    }

    /// A step that could not be completed; the state from before the step is kept.
    pub fn discard(message: impl Into<String>) -> FmiError {
        FmiError {
            status: Status::Discard,
            message: message.into(),
            instance_failed: false,
        }
    }
}

impl fmt::Display for FmiError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for FmiError {}

/// Result of a call of the safe layer.
pub type FmiResult<T> = Result<T, FmiError>;
