//! FMI 2.0 Co-Simulation layer (owned by the FMI work).
