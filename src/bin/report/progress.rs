//! A progress bar on stderr.

use std::io::Write as _;
use std::time::Instant;

pub struct Progress {
    total: usize,
    done: usize,
    start: Instant,
}

impl Progress {
    pub fn new(total: usize) -> Progress {
        Progress {
            total,
            done: 0,
            start: Instant::now(),
        }
    }

    /// One more item done; `what` is the next one.
    pub fn tick(&mut self, what: &str) {
        self.done += 1;
        let width = 30;
        let filled = width * self.done / self.total.max(1);
        let bar: String = "#".repeat(filled) + &"-".repeat(width - filled);
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r[{bar}] {}/{} {:>5.0} s  {:<60}",
            self.done,
            self.total,
            self.start.elapsed().as_secs_f64(),
            what.chars().take(60).collect::<String>()
        );
        let _ = err.flush();
    }

    /// End the bar's line.
    pub fn finish(&self) {
        eprintln!();
    }
}
