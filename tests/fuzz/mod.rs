//! The fuzz harness of the FMI C boundary: seeded random call sequences through the exported
//! FMI 2.0 functions, in process, judged by an oracle written from the standard and
//! docs/fmu.md, and per sequence the generators of [`extended`] (forged pre-initialization
//! states, in-range extremes with a wall-time oracle, freed and foreign handles, FMI 3.0
//! call sequences), and the parameters across their whole declared ranges with a wall-time
//! oracle ([`ranges`]).

pub mod extended;
pub mod fmu;
pub mod hostile;
pub mod legal;
pub mod oracle;
pub mod ranges;
pub mod rng;
pub mod sequence;
