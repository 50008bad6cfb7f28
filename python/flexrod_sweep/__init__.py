"""Parameter sweeps of the flexrod FMU on Dask."""
from .spec import SpecError, load
from .sweep import run_sweep

__all__ = ["SpecError", "load", "run_sweep"]
