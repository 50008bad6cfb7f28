//! Child processes with a time limit: the tests whose subject could hang or exhaust memory run
//! it in a child, killed and failed past its limit.

use std::process::{Child, ExitStatus};
use std::time::{Duration, Instant};

/// Wait for `child` at most `limit` (polling every 20 ms); past it, kill it and fail naming
/// `what`.
pub fn wait_within(child: &mut Child, limit: Duration, what: &str) -> ExitStatus {
    let t0 = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("the child's status") {
            return status;
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what}: the child ran past {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}
