//! The functions of the Model Exchange and Scheduled Execution interfaces (FMI 3.0, 3 and 5).
//! The description declares neither, and an instance of them is never created
//! (`fmi3InstantiateModelExchange`, `fmi3InstantiateScheduledExecution` return NULL), but
//! importers such as FMPy resolve every `fmi3*` symbol of the library when they load it, so
//! they are exported too; called with a Co-Simulation instance they return `fmi3Error`.

use super::lifecycle::not_provided;
use super::{fmi3Boolean, fmi3Float64, fmi3Instance, fmi3Status, fmi3ValueReference};

const NOT_MODEL_EXCHANGE: &str =
    "it belongs to Model Exchange, and this FMU implements only Co-Simulation";
const NOT_SCHEDULED: &str =
    "it belongs to Scheduled Execution, and this FMU implements only Co-Simulation";

macro_rules! not_interface {
    ($why:ident: $($name:ident($($arg:ident: $ty:ty),*);)+) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: fmi3Instance, $($arg: $ty),*) -> fmi3Status {
            $(let _ = $arg;)*
            unsafe { not_provided(instance, stringify!($name), $why) }
        }
    )+};
}

not_interface! { NOT_MODEL_EXCHANGE:
    fmi3EnterContinuousTimeMode();
    fmi3CompletedIntegratorStep(no_set_state: fmi3Boolean, enter_event_mode: *mut fmi3Boolean, terminate: *mut fmi3Boolean);
    fmi3SetTime(time: fmi3Float64);
    fmi3SetContinuousStates(states: *const fmi3Float64, n: usize);
    fmi3GetContinuousStateDerivatives(derivatives: *mut fmi3Float64, n: usize);
    fmi3GetEventIndicators(indicators: *mut fmi3Float64, n: usize);
    fmi3GetContinuousStates(states: *mut fmi3Float64, n: usize);
    fmi3GetNominalsOfContinuousStates(nominals: *mut fmi3Float64, n: usize);
    fmi3GetNumberOfEventIndicators(n: *mut usize);
    fmi3GetNumberOfContinuousStates(n: *mut usize);
}

not_interface! { NOT_SCHEDULED:
    fmi3ActivateModelPartition(clock: fmi3ValueReference, activation_time: fmi3Float64);
}
