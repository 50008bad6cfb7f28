//! FMU states: `fmi2GetFMUstate`, `fmi2SetFMUstate`, `fmi2FreeFMUstate` and serialization.
//! The saved state and its byte form: [`crate::fmi::fmu_state`].

use std::sync::atomic::{AtomicUsize, Ordering};

use super::Instance;
use crate::cosimulation::CoSimulationModel;
use crate::fmi::fmu_state::{self, FmuState, Header};
use crate::fmi::state_machine::Call;
use crate::fmi::status::{FmiError, FmiResult, Status};

/// Handles of FMU states are unique across all instances of the process, so a state of
/// another instance is recognized as foreign.
static NEXT_STATE_HANDLE: AtomicUsize = AtomicUsize::new(1);

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    fn capture(&self) -> FmuState {
        FmuState {
            header: Header {
                machine: self.state,
                experiment: self.experiment,
                last_step: self.last_step,
            },
            model: self.model.save(),
        }
    }

    fn saved(&self, handle: usize) -> FmiResult<&FmuState> {
        self.fmu_states.get(&handle).ok_or_else(|| {
            FmiError::rejected(format!(
                "FMU state {handle:#x} is not a state of this instance (never created here, or already freed)"
            ))
        })
    }

    /// The handle to store a state under: `existing` if it is a live state of this instance
    /// (it is overwritten), else a new one (NULL, or a handle of another instance or one
    /// already freed: that handle is left alone).
    fn handle_for(&self, existing: Option<usize>) -> usize {
        match existing {
            Some(h) if self.fmu_states.contains_key(&h) => h,
            _ => NEXT_STATE_HANDLE.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// `fmi2GetFMUstate`: a new handle, or `existing` overwritten if it is this instance's.
    pub fn get_fmu_state(&mut self, existing: Option<usize>) -> FmiResult<usize> {
        let state = self.capture();
        let handle = self.handle_for(existing);
        self.fmu_states.insert(handle, state);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(handle)
    }

    /// `fmi2SetFMUstate`: everything, including the state machine's state, as when saved.
    pub fn set_fmu_state(&mut self, handle: usize) -> FmiResult<Status> {
        self.saved(handle)?;
        let saved = &self.fmu_states[&handle];
        self.model
            .restore(&saved.model)
            .map_err(FmiError::rejected)?;
        self.experiment = saved.header.experiment;
        self.last_step = saved.header.last_step;
        self.state = saved.header.machine;
        self.failure = None;
        Ok(Status::Ok)
    }

    /// `fmi2FreeFMUstate`.
    pub fn free_fmu_state(&mut self, handle: usize) -> FmiResult<Status> {
        self.saved(handle)?;
        self.fmu_states.remove(&handle);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(Status::Ok)
    }

    /// Bytes of a saved state (computed once per handle).
    fn serialized(&mut self, handle: usize) -> FmiResult<&[u8]> {
        let cached = matches!(&self.serialized, Some((h, _)) if *h == handle);
        if !cached {
            self.saved(handle)?;
            let saved = &self.fmu_states[&handle];
            let model_bytes = self
                .model
                .write_saved(&saved.model)
                .map_err(FmiError::rejected)?;
            let bytes = fmu_state::serialize(&self.guid, &saved.header, &model_bytes);
            self.serialized = Some((handle, bytes));
        }
        Ok(self
            .serialized
            .as_ref()
            .map(|(_, b)| b.as_slice())
            .unwrap_or(&[]))
    }

    /// `fmi2SerializedFMUstateSize`.
    pub fn serialized_size(&mut self, handle: usize) -> FmiResult<usize> {
        Ok(self.serialized(handle)?.len())
    }

    /// `fmi2SerializeFMUstate`: `out` must have exactly the size reported.
    pub fn serialize_fmu_state(&mut self, handle: usize, out: &mut [u8]) -> FmiResult<Status> {
        let standard = self.standard;
        let bytes = self.serialized(handle)?;
        if out.len() != bytes.len() {
            return Err(FmiError::rejected(format!(
                "size = {} bytes is wrong: allowed {} (from {})",
                out.len(),
                bytes.len(),
                Call::SerializedFMUstateSize.name(standard)
            )));
        }
        out.copy_from_slice(bytes);
        Ok(Status::Ok)
    }

    /// `fmi2DeSerializeFMUstate`: a new handle, or `existing` overwritten if it is this
    /// instance's (a handle of another instance, e.g. the one the bytes were serialized from,
    /// gets a new handle here). Foreign, truncated, corrupted or other-model bytes, and every
    /// field outside its range (the table in [`crate::fmi::fmu_state`]), are rejected and
    /// nothing changes.
    pub fn deserialize_fmu_state(
        &mut self,
        bytes: &[u8],
        existing: Option<usize>,
    ) -> FmiResult<usize> {
        let rejected = |m: String| FmiError::rejected(format!("serialized state rejected: {m}"));
        let (header, model_bytes) =
            fmu_state::deserialize(&self.guid, self.standard, bytes).map_err(rejected)?;
        let model = self.model.read_saved(model_bytes).map_err(rejected)?;
        if header.machine.is_stepping() {
            let Some(time) = self.model.saved_time(&model) else {
                return Err(rejected(format!(
                    "machine state {} without a built model (a state after initialization always holds one)",
                    header.machine.name()
                )));
            };
            fmu_state::check_time(time, &header.experiment).map_err(rejected)?;
        }
        let state = FmuState { header, model };
        let handle = self.handle_for(existing);
        self.fmu_states.insert(handle, state);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(handle)
    }
}
