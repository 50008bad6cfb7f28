//! Panics stop at the FMI boundary.
//!
//! [`catch`] runs a closure with `catch_unwind` and turns a panic into its message, with the
//! source location. While a guarded closure runs, the panic hook records the message instead
//! of printing it to the host's stderr: it reaches the importer through its logger. Outside
//! guarded closures the previous hook is used unchanged.

use std::cell::{Cell, RefCell};
use std::panic::{self, UnwindSafe};
use std::sync::Once;

thread_local! {
    static GUARDED: Cell<u32> = const { Cell::new(0) };
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

static INSTALL_HOOK: Once = Once::new();

fn install_hook() {
    INSTALL_HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            // try_with: during thread teardown the thread-locals may be gone; then the
            // previous hook reports the panic.
            if GUARDED.try_with(Cell::get).unwrap_or(0) > 0 {
                let location = info
                    .location()
                    .map(|l| format!(" at {}:{}", l.file(), l.line()))
                    .unwrap_or_default();
                let message = panic_text(info.payload());
                let text = format!("{message}{location}");
                let _ = LAST_PANIC.try_with(|p| {
                    if let Ok(mut slot) = p.try_borrow_mut() {
                        *slot = Some(text);
                    }
                });
            } else {
                previous(info);
            }
        }));
    });
}

/// Run `f`; a panic becomes `Err(message)`.
pub fn catch<T>(f: impl FnOnce() -> T + UnwindSafe) -> Result<T, String> {
    install_hook();
    let _ = GUARDED.try_with(|g| g.set(g.get() + 1));
    let result = panic::catch_unwind(f);
    let _ = GUARDED.try_with(|g| g.set(g.get().saturating_sub(1)));
    result.map_err(|payload| {
        LAST_PANIC
            .try_with(|p| p.try_borrow_mut().ok().and_then(|mut slot| slot.take()))
            .ok()
            .flatten()
            .unwrap_or_else(|| panic_text(payload.as_ref()))
    })
}

/// Message of a caught panic payload.
pub(crate) fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic payload".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panic_becomes_message_with_location() {
        let e = catch(|| -> u32 { panic!("boom {}", 7) }).unwrap_err();
        assert!(e.starts_with("boom 7 at "), "{e}");
        assert!(e.contains("guard.rs"), "{e}");
        assert_eq!(catch(|| 5).unwrap(), 5);
    }
}
