//! The fuzz harness of the FMI 2.0 C boundary: seeded random call sequences through
//! the exported functions, in process, judged by an oracle written from the standard and
//! docs/fmu.md.

pub mod fmu;
pub mod hostile;
pub mod legal;
pub mod oracle;
pub mod rng;
pub mod sequence;
