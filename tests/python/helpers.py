"""Shared helpers of the FMU tests: building, reference results, a capturing logger, a
co-simulation loop driven through fmpy's FMU2Slave."""

import csv
import ctypes
import math
import subprocess
import tomllib
from pathlib import Path

import numpy as np
from fmpy import calloc, free, read_model_description
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)

ROOT = Path(__file__).resolve().parents[2]

# The default experiment of scenes/benchmark.toml (a whole number of steps: 838 x 1e-4 s).
with open(ROOT / "scenes" / "benchmark.toml", "rb") as _f:
    EXPERIMENT = tomllib.load(_f)["experiment"]
STOP = EXPERIMENT["stop_time"]
DT = EXPERIMENT["step_size"]

OUTPUTS = [
    "rod.deflection",
    "rod.deflection_rel",
    "pinB.force_x",
    "pinB.force_y",
    "pinC.force_x",
    "pinC.force_y",
    "crank.torque",
    "slider.position",
    "slider.velocity",
]


def cargo(*args):
    """Run cargo in the workspace; raise with its output on failure."""
    result = subprocess.run(["cargo", *args], cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"cargo {' '.join(args)} failed:\n{result.stdout}\n{result.stderr}")
    return result.stdout


def build_fmu(out_dir, scene=None):
    """`cargo run --release -p fmu -- [scene] --out out_dir`; returns the .fmu path."""
    args = ["run", "--release", "-q", "-p", "fmu", "--"]
    if scene is not None:
        args.append(str(scene))
    args += ["--out", str(out_dir)]
    stdout = cargo(*args)
    for line in stdout.splitlines():
        if line.startswith("wrote ") and ".fmu" in line:
            return Path(line.split(" ")[1])
    raise RuntimeError(f"no .fmu reported by the packager:\n{stdout}")


def reference(csv_path, accel=0.0, steps=None, scene=None):
    """The core's own run of the scene's default experiment (flexrod::Simulation, no FMI), at
    the communication points: dict name -> array, with "time"."""
    args = ["run", "--release", "-q", "-p", "fmu", "--"]
    if scene is not None:
        args.append(str(scene))
    args += ["--no-package", "--csv", str(csv_path)]
    if accel:
        args += ["--accel", repr(accel)]
    if steps:
        args += ["--steps", ",".join(repr(h) for h in steps)]
    cargo(*args)
    with open(csv_path) as f:
        header = next(csv.reader(f))
    data = np.loadtxt(csv_path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def assert_close(actual, expected, rtol=1e-9, what=""):
    """Relative agreement, with the absolute floor scaled by the signal's peak."""
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    assert actual.shape == expected.shape, f"{what}: shape {actual.shape} != {expected.shape}"
    scale = max(np.max(np.abs(expected)), 1e-300)
    np.testing.assert_allclose(actual, expected, rtol=rtol, atol=rtol * scale, err_msg=what)


class LogCapture:
    """fmi2CallbackFunctions whose logger records (status, category, message), and the
    componentEnvironment and instanceName it was called with. `hook(status, text)`, if set,
    runs inside the logger callback (to test re-entrant calls)."""

    def __init__(self, environment=None):
        self.messages = []
        self.callers = []  # (componentEnvironment, instanceName) per message
        self.hook = None

        def log(env, instance_name, status, category, message):
            # The FMU escapes '%' as '%%' (the message is a printf format).
            text = message.decode("utf-8", "replace").replace("%%", "%")
            self.messages.append((status, category.decode(), text))
            self.callers.append((env, instance_name))
            if self.hook is not None:
                self.hook(status, text)

        self._logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        if environment is not None:
            self.callbacks.componentEnvironment = environment

    def text(self):
        return "\n".join(m for _, _, m in self.messages)

    def last(self):
        return self.messages[-1][2] if self.messages else ""

    def clear(self):
        self.messages.clear()


class Slave:
    """One FMU instance driven through fmpy's FMU2Slave with a capturing logger."""

    def __init__(self, unzipdir, name="instance", logging_on=False, guid=None, environment=None):
        self.md = read_model_description(str(unzipdir))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.log = LogCapture(environment)
        self.fmu = FMU2Slave(
            guid=guid or self.md.guid,
            unzipDirectory=str(unzipdir),
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate(callbacks=self.log.callbacks, loggingOn=logging_on)
        self.time = None

    def get(self, *names):
        return self.fmu.getReal([self.vr[n] for n in names])

    def set(self, **values):
        names = [n.replace("__", ".") for n in values]
        self.fmu.setReal([self.vr[n] for n in names], list(values.values()))

    def init(self, start=0.0, stop=None, params=None, angle=0.0, speed=150.0, accel=None):
        self.fmu.setupExperiment(startTime=start, stopTime=stop)
        if params:
            for name, value in params.items():
                self.fmu.setReal([self.vr[name]], [value])
        self.fmu.enterInitializationMode()
        self.fmu.setReal([self.vr["crank.angle"], self.vr["crank.speed"]], [angle, speed])
        if accel is not None:
            self.fmu.setRealInputDerivatives([self.vr["crank.speed"]], [1], [accel])
        self.fmu.exitInitializationMode()
        self.time = start

    def outputs(self):
        return self.get(*OUTPUTS)

    def raw(self, name, *argtypes):
        """The C function `name` of the FMU's library with these argument types, returning
        the fmi2Status (a fresh ctypes function object: fmpy's own stay untouched)."""
        f = self.fmu.dll[name]
        f.argtypes = list(argtypes)
        f.restype = ctypes.c_int
        return f

    def free(self):
        self.fmu.freeInstance()


def schedule(start, stop, dt=None, steps=None):
    """Communication points as the packager's --simulate and fmpy's simulate_fmu make them."""
    times = [start]
    time, n = start, 0
    while not (time > stop or math.isclose(time, stop)):
        nxt = start + (n + 1) * dt if steps is None else time + steps[n % len(steps)]
        if nxt > stop and not math.isclose(nxt, stop):
            nxt = stop
        time = nxt
        n += 1
        times.append(time)
    return times


def crank_input(t, start=0.0, omega0=150.0, accel=0.0):
    """The crank law of the reference run (same operations, same rounding)."""
    s = t - start
    return 0.0 + omega0 * s + 0.5 * accel * s * s, omega0 + accel * s


def run_loop(slave, times, accel=0.0, derivatives=True, omega0=150.0, between=None, start=0.0):
    """Set the crank input of the law started at `start` at every point (and its
    derivative), step; outputs per point (the first row before any step)."""
    out = [slave.outputs()]
    for k in range(len(times) - 1):
        t, h = times[k], times[k + 1] - times[k]
        angle, speed = crank_input(t, start, omega0, accel)
        slave.set(crank__angle=angle, crank__speed=speed)
        if derivatives and accel:
            slave.fmu.setRealInputDerivatives([slave.vr["crank.speed"]], [1], [accel])
        slave.fmu.doStep(t, h)
        if between is not None:
            between(k)
        out.append(slave.outputs())
    return np.array(out)


def restore_fmpy_default_logger():
    """Point FMPy's native logger proxy back at its default logger. The proxy (FMPy 0.3) is one
    per process: simulate_fmu(logger=f) points it at f, and a later simulate_fmu without a
    logger of its own then calls f, collected by then, at the FMU's first message, which
    crashes the process (docs/usage.md, "Use from other tools": FMPy's logger)."""
    import fmpy.fmi2 as fmi2
    from fmpy.logging import addLoggerProxy

    fmi2.defaultCallbacks.logger = fmi2.fmi2CallbackLoggerTYPE(fmi2.printLogMessage)
    addLoggerProxy(ctypes.byref(fmi2.defaultCallbacks))


def unexpected_warnings(slave):
    """The messages above fmi2OK but the error estimate's one warning (the benchmark rod at
    150 rad/s: the estimate passes the default tolerance, docs/fmu.md, "Model class and error
    estimate")."""
    return [
        m
        for status, _, m in slave.log.messages
        if status > 0 and not (status == 1 and m.startswith("rod.error_estimate"))
    ]
