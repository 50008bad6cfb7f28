"""Parameter sweeps of the flexrod FMU on Dask."""

from .spec import Spec, SpecError, load, run_id
from .sweep import load_series, regenerate, run_sweep

__all__ = ["Spec", "SpecError", "load", "load_series", "regenerate", "run_id", "run_sweep"]
