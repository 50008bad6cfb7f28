//! The rod model's saved state in bytes: the model's part of a serialized FMU state (the
//! interface wraps it in its own header). Little endian, one layout (`docs/fmu.md`, "Saved
//! states"):
//!
//! ```text
//! started u8,
//! inputs: angle, speed, slider force, acceleration, jerk f64, acceleration source u8,
//!         jerk source u8, force changed u8 (Inputs::to_bytes),
//! parameters: the scene (u32 length + TOML),
//! simulation present u8 (+ u64 length + the simulation's bytes: Simulation::state_to_bytes,
//!         the model fingerprint of its scene, then the mechanism's state)
//! ```
//!
//! Every field is checked when read: the inputs against the windows of their set calls, the
//! scene against its keys' ranges and against this model (only declared parameters
//! changed: [`super::binding::check_same_model`]), the simulation against its fingerprint and
//! the ranges of an accepted step (`Simulation::restore_state_bytes`).

use super::inputs::Inputs;
use super::instance::{RodModel, SavedModel};
use crate::bytes::{ByteReader, ByteWriter};
use crate::error::ModelError;

impl RodModel {
    /// The bytes of `saved`; the current state is left as it was.
    pub fn saved_to_bytes(&mut self, saved: &SavedModel) -> Result<Vec<u8>, ModelError> {
        let simulation = self.simulation_bytes(saved)?;
        let mut w = ByteWriter::default();
        w.flag(saved.started());
        w.raw(&saved.inputs_bytes());
        w.bytes_u32(saved.parameters_text().as_bytes());
        w.flag(simulation.is_some());
        if let Some(bytes) = simulation {
            w.bytes_u64(&bytes);
        }
        Ok(w.bytes)
    }

    /// A saved model from bytes [`Self::saved_to_bytes`] wrote, every field checked.
    pub fn saved_from_bytes_checked(&mut self, bytes: &[u8]) -> Result<SavedModel, String> {
        let mut r = ByteReader::new(bytes);
        let started = r.flag("the started flag")?;
        let mut inputs = [0u8; Inputs::BYTES];
        inputs.copy_from_slice(r.take(Inputs::BYTES, "the inputs")?);
        let parameters = r.str_u32("the scene")?;
        let simulation = if r.flag("the simulation flag")? {
            Some(r.bytes_u64("the simulation")?)
        } else {
            None
        };
        r.finish("the model's state")?;
        let saved = SavedModel::from_parts(started, &inputs, parameters)?;
        self.check_same_model(&saved)?;
        // The interface says the state was rejected; the simulation's own message says so too.
        self.saved_from_bytes(saved, simulation).map_err(|e| {
            let message = e.to_string();
            match message.strip_prefix("serialized state rejected: ") {
                Some(reason) => reason.to_string(),
                None => message,
            }
        })
    }
}
