#!/usr/bin/env python3
"""The FMI 3.0 FMU through FMPy: the crank starts from rest at a constant acceleration, given with
the crank acceleration and jerk as inputs.

    .venv/bin/python examples/fmi3_fmpy.py [FMU]

FMU: `target/fmu/FlexibleSliderCrank-fmi3.fmu` by default (`cargo run --release -p fmu` writes
it). FMI 3.0 has no input derivatives: the crank acceleration and jerk of the input law are the
inputs `crank.acceleration` and `crank.jerk` (docs/fmu.md, "The crank acceleration and jerk").
The input table gives them with the angle and the speed, so FMPy finds every input of the FMU in
it (an input left out of the table keeps its start value, and FMPy warns "missing input for
variable"). The table has a row at every communication point: FMPy interpolates it linearly, and
the angle of an accelerating crank is not linear in time.
"""

import sys
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu

FMU = Path(__file__).resolve().parents[1] / "target" / "fmu" / "FlexibleSliderCrank-fmi3.fmu"

SPEED = 0.0  # rad/s at t = 0: from rest
ACCELERATION = 1800.0  # rad/s^2: 150.8 rad/s at the stop time
STOP = 0.0838  # s, the default experiment's stop time
STEP = 1e-4  # s, its communication step


def crank_table(stop=STOP, step=STEP, speed=SPEED, acceleration=ACCELERATION):
    """The input table: a row at every communication point, every input of the FMU."""
    t = np.arange(round(stop / step) + 1) * step
    rows = zip(
        t,
        speed * t + 0.5 * acceleration * t * t,  # crank.angle, rad
        speed + acceleration * t,  # crank.speed, rad/s
        np.full_like(t, acceleration),  # crank.acceleration, rad/s^2
        np.zeros_like(t),  # crank.jerk, rad/s^3
        np.zeros_like(t),  # slider.force, N
    )
    names = ["crank.angle", "crank.speed", "crank.acceleration", "crank.jerk", "slider.force"]
    return np.array(list(rows), dtype=[("time", float)] + [(n, float) for n in names])


def run(fmu=FMU):
    """The run: FMPy's result (a structured array, `rod.shape` one array per point). The crank
    speeds up: `crank.design_speed` tells `rod.model = auto` the speed it will reach."""
    return simulate_fmu(
        str(fmu),
        stop_time=STOP,
        step_size=STEP,
        output_interval=STEP,
        input=crank_table(),
        start_values={"crank.design_speed": SPEED + ACCELERATION * STOP},
        output=[
            "rod.deflection_rel",
            "pinB.force_x",
            "pinB.force_y",
            "rod.shape",
            "rod.error_estimate",
        ],
    )


def main():
    fmu = Path(sys.argv[1]) if len(sys.argv) > 1 else FMU
    result = run(fmu)
    end = SPEED + ACCELERATION * STOP
    print(f"crank from {SPEED:.0f} to {end:.1f} rad/s at {ACCELERATION:.0f} rad/s^2, {STOP} s")
    print(f"peak |v_mid/L| = {abs(result['rod.deflection_rel']).max():.4f}")
    pin_b = np.hypot(result["pinB.force_x"], result["pinB.force_y"])
    print(f"peak |pin B force| = {pin_b.max():.1f} N")
    shape = result["rod.shape"][-1] * 1e3
    print("rod.shape at the end, mm: " + " ".join(f"{v:.2f}" for v in shape))
    print(f"rod.error_estimate at the end = {result['rod.error_estimate'][-1]:.1e}")


if __name__ == "__main__":
    main()
