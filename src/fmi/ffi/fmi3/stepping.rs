//! Co-simulation: `fmi3DoStep` with its out-arguments, `fmi3EnterStepMode` (only with event
//! mode, which this FMU does not have), and the derivatives it does not provide (FMI 3.0,
//! 4.2 and 2.3.11). The crank acceleration and jerk, input derivatives in FMI 2.0, are the
//! inputs `crank.acceleration` and `crank.jerk` here (FMI 3.0 Co-Simulation has no input
//! derivatives).

use super::super::component::dispatch;
use super::super::convert::out;
use super::lifecycle::not_provided;
use super::{fmi3Boolean, fmi3Float64, fmi3Instance, fmi3Int32, fmi3Status, fmi3ValueReference};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;

#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    instance: fmi3Instance,
    currentCommunicationPoint: fmi3Float64,
    communicationStepSize: fmi3Float64,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    eventHandlingNeeded: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    earlyReturn: *mut fmi3Boolean,
    lastSuccessfulTime: *mut fmi3Float64,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::DoStep, |i| {
            // All out-arguments first: a NULL one rejects the call before anything changes.
            let event = out(eventHandlingNeeded, "eventHandlingNeeded")?;
            let terminate = out(terminateSimulation, "terminateSimulation")?;
            let early = out(earlyReturn, "earlyReturn")?;
            let last = out(lastSuccessfulTime, "lastSuccessfulTime")?;
            let result = i.do_step(currentCommunicationPoint, communicationStepSize);
            // No events, never a request to stop, never an early return; the time reached
            // (after a discarded step, the time before it).
            *event = false;
            *terminate = false;
            *early = false;
            *last = i.time();
            result
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterStepMode(instance: fmi3Instance) -> fmi3Status {
    unsafe {
        not_provided(
            instance,
            "fmi3EnterStepMode",
            "this FMU declares hasEventMode=\"false\": it is in Step Mode right after fmi3ExitInitializationMode",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    instance: fmi3Instance,
    _valueReferences: *const fmi3ValueReference,
    _nValueReferences: usize,
    _orders: *const fmi3Int32,
    _values: *mut fmi3Float64,
    _nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::GetRealOutputDerivatives,
            |i| i.get_real_output_derivatives(),
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    instance: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _nUnknowns: usize,
    _knowns: *const fmi3ValueReference,
    _nKnowns: usize,
    _seed: *const fmi3Float64,
    _nSeed: usize,
    _sensitivity: *mut fmi3Float64,
    _nSensitivity: usize,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::GetDirectionalDerivative,
            |i| i.get_directional_derivative(),
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetAdjointDerivative(
    instance: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _nUnknowns: usize,
    _knowns: *const fmi3ValueReference,
    _nKnowns: usize,
    _seed: *const fmi3Float64,
    _nSeed: usize,
    _sensitivity: *mut fmi3Float64,
    _nSensitivity: usize,
) -> fmi3Status {
    unsafe {
        not_provided(
            instance,
            "fmi3GetAdjointDerivative",
            "this FMU declares providesAdjointDerivatives=\"false\"",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
    instance: fmi3Instance,
    _valueReference: fmi3ValueReference,
    _nDependencies: *mut usize,
) -> fmi3Status {
    unsafe {
        not_provided(
            instance,
            "fmi3GetNumberOfVariableDependencies",
            "this FMU declares providesPerElementDependencies=\"false\"; the dependencies are in ModelStructure",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetVariableDependencies(
    instance: fmi3Instance,
    _dependent: fmi3ValueReference,
    _elementIndicesOfDependent: *mut usize,
    _independents: *mut fmi3ValueReference,
    _elementIndicesOfIndependents: *mut usize,
    _dependencyKinds: *mut i32,
    _nDependencies: usize,
) -> fmi3Status {
    unsafe {
        not_provided(
            instance,
            "fmi3GetVariableDependencies",
            "this FMU declares providesPerElementDependencies=\"false\"; the dependencies are in ModelStructure",
        )
    }
}
