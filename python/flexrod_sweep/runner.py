"""Worker side: one FMU instance per process (extracted once into a temporary folder, reused with
fmi2Reset between runs), the crank drive loop, the gas force, the per-run time limit and the
metrics.

Everything here is deterministic: the same run gives bit-identical metrics in any process.

Temporary folders: each process extracts an FMU into `TMP/flexrod_sweep_<pid>_<digest>_*`; the
folder is removed when the runner is released (`release`, called on every worker at the end of a
sweep), at the process's exit (atexit), and, for a process that was killed, by the next process
that extracts an FMU (folders whose process no longer exists).
"""

import atexit
import ctypes
import glob
import hashlib
import math
import os
import shutil
import tempfile
import threading
import time
import zipfile

import numpy as np

STATUS_NAMES = {0: "ok", 1: "warning", 2: "discard", 3: "error", 4: "fatal", 5: "pending"}
TMP_PREFIX = "flexrod_sweep_"

# Per process: (FMU digest, thread) -> Runner (Dask workers use one thread each by default).
_RUNNERS = {}
_LOCK = threading.Lock()


class RunFailed(Exception):
    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message


def fmu_digest(data):
    return hashlib.sha256(data).hexdigest()[:16]


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale_folders(tmp=None):
    """Remove extraction folders of processes that no longer exist; returns how many."""
    n = 0
    for d in glob.glob(os.path.join(tmp or tempfile.gettempdir(), TMP_PREFIX + "*")):
        parts = os.path.basename(d)[len(TMP_PREFIX) :].split("_")
        if not parts or not parts[0].isdigit():
            continue
        if int(parts[0]) != os.getpid() and not _alive(int(parts[0])):
            shutil.rmtree(d, ignore_errors=True)
            n += 1
    return n


def release(digest=None, wait=10.0):
    """Free the runners of this process (of one FMU digest, or all) and remove their folders.
    A runner in the middle of a chunk is waited for up to `wait` seconds, else left to the exit
    of the process (atexit) or to the next process's clean-up of stale folders."""
    with _LOCK:
        keys = [k for k in _RUNNERS if digest is None or k[0] == digest]
    for key in keys:
        runner = _RUNNERS.get(key)
        if runner is None or not runner.busy.acquire(timeout=wait):
            continue
        try:
            with _LOCK:
                if _RUNNERS.get(key) is runner:
                    del _RUNNERS[key]
                    runner.close()
        finally:
            runner.busy.release()
    return os.getpid()


atexit.register(release, None, 0.0)


def get_runner(fmu_bytes_or_path):
    """The runner of this process for the FMU (bytes, or a path readable here): extracted once
    per process into a temporary directory, instantiated once."""
    if isinstance(fmu_bytes_or_path, (bytes, bytearray)):
        data = bytes(fmu_bytes_or_path)
    else:
        with open(fmu_bytes_or_path, "rb") as f:
            data = f.read()
    key = (fmu_digest(data), threading.get_ident())
    with _LOCK:
        runner = _RUNNERS.get(key)
        if runner is None:
            remove_stale_folders()
            unzipdir = tempfile.mkdtemp(prefix=f"{TMP_PREFIX}{os.getpid()}_{key[0]}_")
            try:
                with zipfile.ZipFile(_io_bytes(data)) as z:
                    z.extractall(unzipdir)
                runner = Runner(unzipdir)
            except BaseException:
                shutil.rmtree(unzipdir, ignore_errors=True)
                raise
            _RUNNERS[key] = runner
    return runner


def _io_bytes(data):
    import io

    return io.BytesIO(data)


class Runner:
    """One FMU2Slave with a capturing logger; `run(values, job)` per run."""

    def __init__(self, unzipdir):
        from fmpy import calloc, free, read_model_description
        from fmpy.fmi2 import (
            FMU2Slave,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
        )

        self.unzipdir = unzipdir
        self.busy = threading.Lock()  # held while a chunk runs (release waits for it)
        self.md = read_model_description(unzipdir)
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.all_outputs = [
            v.name for v in self.md.modelVariables if v.causality == "output" and v.type == "Real"
        ]
        self.messages = []

        def log(env, instance_name, status, category, message):
            text = message.decode("utf-8", "replace").replace("%%", "%")
            self.messages.append((status, text))

        self._logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=unzipdir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName="sweep",
        )
        self.fmu.instantiate(callbacks=self.callbacks, loggingOn=False)
        self.fresh = True
        # Raw C functions (fresh ctypes objects) for the hot loop: no per-call conversions.
        dll = self.fmu.dll
        vp, sz = ctypes.c_void_p, ctypes.c_size_t
        dp, ip = ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_int)
        uip = ctypes.POINTER(ctypes.c_uint)

        def raw(name, *argtypes):
            f = dll[name]
            f.argtypes = list(argtypes)
            f.restype = ctypes.c_int
            return f

        self._set_real = raw("fmi2SetReal", vp, uip, sz, dp)
        self._get_real = raw("fmi2GetReal", vp, uip, sz, dp)
        self._set_integer = raw("fmi2SetInteger", vp, uip, sz, ip)
        self._set_boolean = raw("fmi2SetBoolean", vp, uip, sz, ip)
        self._set_deriv = raw("fmi2SetRealInputDerivatives", vp, uip, sz, ip, dp)
        self._do_step = raw("fmi2DoStep", vp, ctypes.c_double, ctypes.c_double, ctypes.c_int)
        self._setup = raw(
            "fmi2SetupExperiment",
            vp,
            ctypes.c_int,
            ctypes.c_double,
            ctypes.c_double,
            ctypes.c_int,
            ctypes.c_double,
        )
        self._enter = raw("fmi2EnterInitializationMode", vp)
        self._exit = raw("fmi2ExitInitializationMode", vp)
        self._reset = raw("fmi2Reset", vp)

    def close(self):
        try:
            self.fmu.freeInstance()
        except Exception:
            pass
        shutil.rmtree(self.unzipdir, ignore_errors=True)

    # -- helpers -------------------------------------------------------------------------

    def _check(self, status, what, worst):
        if status > 1:
            msgs = [m for s, m in self.messages if s >= 2] or [m for _, m in self.messages]
            text = msgs[-1] if msgs else f"{what} returned {STATUS_NAMES.get(status, status)}"
            if not text.startswith(what.split(" ")[0]):
                text = f"{what}: {text}"
            raise RunFailed(STATUS_NAMES.get(status, str(status)), text)
        return max(worst, status)

    def _set_value(self, name, value):
        v = self.vars[name]
        vr = (ctypes.c_uint * 1)(v.valueReference)
        if v.type == "Real":
            return self._set_real(self.fmu.component, vr, 1, (ctypes.c_double * 1)(float(value)))
        if v.type == "Boolean":
            return self._set_boolean(
                self.fmu.component, vr, 1, (ctypes.c_int * 1)(int(bool(value)))
            )
        return self._set_integer(self.fmu.component, vr, 1, (ctypes.c_int * 1)(int(value)))

    def get(self, names):
        n = len(names)
        vrs = (ctypes.c_uint * n)(*[self.vars[x].valueReference for x in names])
        out = (ctypes.c_double * n)()
        self._check(self._get_real(self.fmu.component, vrs, n, out), "fmi2GetReal", 0)
        return list(out)

    # -- one run -------------------------------------------------------------------------

    def run(self, values, job, series=False):
        """Simulate one run. `values`: name -> value already converted for the FMU (enumerations
        as integers; `gas.*` names set the gas force). `job`: see `Spec.job()`. Returns
        (status, message, metrics dict, record dict, time series or None)."""
        self.series = None
        try:
            return (*self._run(values, job, series), self.series)
        except RunFailed as e:
            return e.status, e.message, {}, getattr(self, "_rec", {}), self.series

    def _run(self, values, job, want_series):
        self.messages.clear()
        self._rec = {}
        comp = self.fmu.component
        if not self.fresh:
            self._reset(comp)
        self.fresh = False
        drive, metrics, record = job["drive"], job["metrics"], job["record"]
        outputs, abort = job["outputs"], job["abort"]
        timeout = job.get("timeout")
        worst = 0
        speed = float(values.get("crank.speed", drive["speed"]))
        gas = GasForce(job.get("gas"), values) if job.get("gas") else None
        force = values.get("slider.force")
        law = CrankLaw(drive, speed)
        dt = drive["step"]
        n_steps, n_start_measure, rev_marks = law.schedule(dt)
        t_stop = n_steps * dt
        t_begin = time.perf_counter()
        deadline = t_begin + timeout if timeout else math.inf
        worst = self._check(self._setup(comp, 0, 0.0, 0.0, 1, t_stop), "fmi2SetupExperiment", worst)
        for name, value in values.items():
            if name.startswith("gas.") or self.vars[name].causality == "input":
                continue
            worst = self._check(self._set_value(name, value), f"set {name}", worst)
        worst = self._check(self._enter(comp), "fmi2EnterInitializationMode", worst)
        vr_in = (ctypes.c_uint * 2)(
            self.vars["crank.angle"].valueReference, self.vars["crank.speed"].valueReference
        )
        vr_speed = (ctypes.c_uint * 1)(self.vars["crank.speed"].valueReference)
        vr_force = (ctypes.c_uint * 1)(self.vars["slider.force"].valueReference) if gas else None
        fval = (ctypes.c_double * 1)()
        order = (ctypes.c_int * 1)(1)
        acc = (ctypes.c_double * 1)()
        inp = (ctypes.c_double * 2)()
        if force is not None:
            worst = self._check(self._set_value("slider.force", force), "set slider.force", worst)
        a0, w0, al0 = law(0.0)
        inp[0], inp[1] = a0, w0
        worst = self._check(self._set_real(comp, vr_in, 2, inp), "set crank inputs", worst)
        if gas:
            fval[0] = gas(law(0.5 * dt)[0])
            worst = self._check(self._set_real(comp, vr_force, 1, fval), "set slider.force", worst)
        if al0 != 0.0:
            acc[0] = al0
            worst = self._check(
                self._set_deriv(comp, vr_speed, 1, order, acc), "set crank acceleration", worst
            )
        worst = self._check(self._exit(comp), "fmi2ExitInitializationMode", worst)
        rec = dict(zip(record, self.get(record))) if record else {}
        self._rec = rec

        if want_series:
            # Every output of the FMU at every communication point from t = 0 on.
            outputs = list(dict.fromkeys(list(outputs) + self.all_outputs))
            first = 0
        else:
            first = n_start_measure
        n_out = len(outputs)
        vr_out = (ctypes.c_uint * n_out)(*[self.vars[x].valueReference for x in outputs])
        data = np.empty((n_steps - first + 1, n_out))
        force_hist = np.zeros(n_steps - first + 1) if gas else None
        row = (ctypes.c_double * n_out)()
        abort_idx = [(outputs.index(k), v) for k, v in abort.items()]
        filled = 0
        if first == 0:  # the state after initialization
            self._check(self._get_real(comp, vr_out, n_out, row), "fmi2GetReal", 0)
            data[0] = row
            filled = 1
            if gas:
                force_hist[0] = fval[0]
        status = "ok"
        message = ""
        try:
            for k in range(n_steps):
                t = k * dt
                if k:
                    angle, w, al = law(t)
                    inp[0], inp[1] = angle, w
                    worst = self._check(
                        self._set_real(comp, vr_in, 2, inp), "set crank inputs", worst
                    )
                    if al != 0.0:
                        acc[0] = al
                        worst = self._check(
                            self._set_deriv(comp, vr_speed, 1, order, acc),
                            "set crank acceleration",
                            worst,
                        )
                    if gas:
                        fval[0] = gas(law(t + 0.5 * dt)[0])
                        worst = self._check(
                            self._set_real(comp, vr_force, 1, fval), "set slider.force", worst
                        )
                # A single fmi2DoStep is bounded in time (a fixed communication step); the time
                # limit is checked between steps.
                if time.perf_counter() > deadline:
                    raise RunFailed(
                        "timeout",
                        f"stopped at t = {t:.6g} s of {t_stop:.6g} s: past the "
                        f"run's time limit of {timeout:g} s ([run] timeout)",
                    )
                worst = self._check(
                    self._do_step(comp, t, dt, 1), f"fmi2DoStep at t = {t:.6g} s", worst
                )
                j = k + 1 - first
                if j >= 0 or abort_idx:
                    self._check(self._get_real(comp, vr_out, n_out, row), "fmi2GetReal", 0)
                    for i, limit in abort_idx:
                        x = row[i]
                        if not math.isfinite(x) or abs(x) > limit:
                            raise RunFailed(
                                "diverged",
                                f"|{outputs[i]}| = {x:.4g} > {limit:g} at t = {(k + 1) * dt:.6g} s",
                            )
                    if j >= 0:
                        data[j] = row
                        filled = j + 1
                        if gas:
                            force_hist[j] = fval[0]
        except RunFailed as e:
            if want_series:
                self.series = self._series(
                    law, dt, first, outputs, data[:filled], force_hist, filled
                )
            return e.status, e.message, {}, rec
        if want_series:
            self.series = self._series(law, dt, first, outputs, data, force_hist, len(data))
            data = data[n_start_measure - first :]
            if force_hist is not None:
                force_hist = force_hist[n_start_measure - first :]
        if not np.all(np.isfinite(data)):
            return "diverged", "non-finite output", {}, rec
        if worst == 1:
            status = "warning"
            warn = [m for s, m in self.messages if s == 1]
            message = warn[0] if warn else "fmi2Warning"
        # Revolution boundaries inside the measured window, for growth() and order().
        marks = [m - n_start_measure for m in rev_marks]
        series = {name: data[:, i] for i, name in enumerate(outputs)}
        if gas:
            series["slider.force"] = force_hist
        steps = np.arange(n_start_measure, n_steps + 1)
        series["crank.angle"] = law.angles(steps * dt)
        needs = {parse_metric(m)[1] for m in metrics}
        if needs & set(DERIVED):
            series.update(derived(series, self.get(["crank.length"])[0], job.get("props", {})))
        return status, message, compute_metrics(metrics, series, marks, job.get("props", {})), rec

    def _series(self, law, dt, first, outputs, data, force_hist, n):
        t = (np.arange(n) + first) * dt
        cols = {"time": t, "crank.angle": law.angles(t)}
        for i, name in enumerate(outputs):
            cols[name] = data[:n, i].copy()
        if force_hist is not None:
            cols["slider.force"] = force_hist[:n].copy()
        return cols


class GasForce:
    """A gas-force pulse on the piston, through the FMU's `slider.force` input (N, along +x):
    F = -peak exp(-((theta - angle) / width)^2), theta the crank angle wrapped to one cycle of
    `cycle` revolutions around `angle` (2: a four-stroke engine fires once every two revolutions).
    Negative: it pushes the piston towards the crank and compresses the rod. The force is held
    over each communication step at its value at the step's midpoint."""

    KEYS = ("peak", "angle", "width", "cycle")

    def __init__(self, cfg, values):
        c = {**cfg, **{k[4:]: v for k, v in values.items() if k.startswith("gas.")}}
        self.peak = float(c["peak"])
        self.angle = math.radians(float(c.get("angle", 15.0)))
        self.width = math.radians(float(c.get("width", 20.0)))
        self.period = 2 * math.pi * float(c.get("cycle", 2))

    def __call__(self, theta):
        d = (theta - self.angle + 0.5 * self.period) % self.period - 0.5 * self.period
        d /= self.width
        return -self.peak * math.exp(-d * d)


class CrankLaw:
    """Crank angle, speed and acceleration at time t for the drive of a run.

    constant: a start from rest with uniform acceleration over `start_time` (0: abrupt start at
    full speed), then constant speed; transient and measured spans in revolutions at full speed.
    ramp: uniform acceleration from `speed_from` to `speed_to` over `duration`.
    """

    def __init__(self, drive, speed):
        self.kind = drive["kind"]
        self.drive = drive
        if self.kind == "constant":
            self.w = speed
            self.ts = drive["start_time"]
            self.a = speed / self.ts if self.ts > 0 else 0.0
        else:
            self.w0 = drive["speed_from"]
            self.ts = drive["duration"]
            self.a = (drive["speed_to"] - drive["speed_from"]) / self.ts

    def __call__(self, t):
        if self.kind == "constant":
            if t < self.ts:
                return 0.5 * self.a * t * t, self.a * t, self.a
            th0 = 0.5 * self.a * self.ts * self.ts
            return th0 + self.w * (t - self.ts), self.w, 0.0
        return self.w0 * t + 0.5 * self.a * t * t, self.w0 + self.a * t, self.a

    def angles(self, t):
        """Crank angles at the times `t` (array)."""
        t = np.asarray(t, dtype=float)
        if self.kind == "constant":
            th0 = 0.5 * self.a * self.ts * self.ts
            return np.where(t < self.ts, 0.5 * self.a * t * t, th0 + self.w * (t - self.ts))
        return self.w0 * t + 0.5 * self.a * t * t

    def schedule(self, dt):
        """(number of steps, first measured step index, step indices of revolution marks)."""
        if self.kind == "constant":
            period = 2 * math.pi / abs(self.w)
            n_start = round(self.ts / dt)
            self.ts = n_start * dt  # the start ends on a communication point
            self.a = self.w / self.ts if self.ts > 0 else 0.0
            trans = max(
                self.drive["transient_revolutions"] * period, self.drive["min_transient_time"]
            )
            n_meas0 = n_start + math.ceil(trans / dt - 1e-9)
            n_rev = self.drive["measure_revolutions"]
            n_total = n_meas0 + math.ceil(n_rev * period / dt - 1e-9)
            marks = [n_meas0 + round(i * period / dt) for i in range(n_rev + 1)]
            return n_total, n_meas0, marks
        n_total = math.ceil(self.ts / dt - 1e-9)
        self.a = (self.drive["speed_to"] - self.drive["speed_from"]) / (n_total * dt)
        n_meas0 = min(n_total, math.ceil(self.drive["min_transient_time"] / dt - 1e-9))
        return n_total, n_meas0, [n_meas0, n_total]


# Derived outputs a metric may name besides the FMU's own: name -> FMU variables it needs.
DERIVED = {
    # Axial force of the rod (tension > 0), the mean of its two ends along the chord B -> C:
    # N = (F_B . e - F_C . e) / 2, F the force of the rod on the pin, e the unit chord.
    "rod.axial_force": [
        "pinB.force_x",
        "pinB.force_y",
        "pinC.force_x",
        "pinC.force_y",
        "crank.angle",
        "slider.position",
    ],
    # Normal stress at the two outer fibres of the rod's midpoint section ([section] area,
    # area_moment, fibre_distance of that section): N/A + M c/I (the fibre on the +v side) and
    # N/A - M c/I. Two columns: metrics report the governing fibre (see compute_metrics).
    "section.stress": ["rod.axial_force_mid", "rod.bending_moment_mid"],
    # N/A at the midpoint section.
    "section.axial_stress": ["rod.axial_force_mid"],
}
# What each derived output needs from the spec's [section] table.
DERIVED_PROPS = {
    "section.stress": ["area", "area_moment", "fibre_distance"],
    "section.axial_stress": ["area"],
}
DERIVED_UNITS = {
    "rod.axial_force": "N",
    "section.stress": "Pa",
    "section.axial_stress": "Pa",
    "slider.force": "N",
    "crank.angle": "rad",
}


def derived(s, r, props):
    out = {}
    if "pinB.force_x" in s and "slider.position" in s:
        bx, by = r * np.cos(s["crank.angle"]), r * np.sin(s["crank.angle"])
        ex, ey = s["slider.position"] - bx, -by
        n = np.hypot(ex, ey)
        ex, ey = ex / n, ey / n
        nb = s["pinB.force_x"] * ex + s["pinB.force_y"] * ey
        nc = -(s["pinC.force_x"] * ex + s["pinC.force_y"] * ey)
        out["rod.axial_force"] = 0.5 * (nb + nc)
    sec = props.get("section", {})
    if "rod.axial_force_mid" in s and "area" in sec:
        axial = s["rod.axial_force_mid"] / sec["area"]
        out["section.axial_stress"] = axial
        if "rod.bending_moment_mid" in s and "area_moment" in sec and "fibre_distance" in sec:
            bend = s["rod.bending_moment_mid"] * sec["fibre_distance"] / sec["area_moment"]
            out["section.stress"] = np.stack([axial + bend, axial - bend], axis=1)
    return out


METRIC_KINDS = (
    "max_abs",
    "max",
    "min",
    "mean",
    "range",
    "rms",
    "growth",
    "amplitude",
    "midrange",
    "goodman",
    "buckling_margin",
    "at",
    "order",
)
# Kinds that take a number after the output: at(X, crank angle in degrees), order(X, k).
ARG_KINDS = ("at", "order")
DIMENSIONLESS_KINDS = ("growth", "goodman", "buckling_margin")


def goodman(sa, sm, material):
    """Fatigue safety factor by the modified Goodman line (J. E. Shigley, C. R. Mischke,
    R. G. Budynas, "Mechanical Engineering Design", McGraw-Hill: 1/n = sigma_a / S_e + sigma_m /
    S_u for sigma_m >= 0; for a compressive mean stress the amplitude alone governs, n = S_e /
    sigma_a)."""
    se, su = material["endurance_strength"], material["ultimate_strength"]
    if sa <= 0 and sm <= 0:
        return math.inf
    if sm >= 0:
        return 1.0 / (sa / se + sm / su)
    return se / sa


def critical_load(props):
    """Buckling load of the rod as a pinned column (effective length K L): Euler,
    pi^2 E I / (K L)^2, for a slenderness K L / r at or above sqrt(2 pi^2 E / S_y); Johnson's
    parabola, A (S_y - (S_y K L / (2 pi r))^2 / E), below it (r = sqrt(I / A); without a yield
    strength, Euler throughout)."""
    b = props["buckling"]
    e, i, a, le = b["youngs_modulus"], b["area_moment"], b["area"], b["end_factor"] * b["length"]
    r = math.sqrt(i / a)
    sy = props.get("material", {}).get("yield_strength")
    euler = math.pi**2 * e * i / le**2
    if sy is None or le / r >= math.sqrt(2 * math.pi**2 * e / sy):
        return euler
    return a * (sy - (sy * le / (2 * math.pi * r)) ** 2 / e)


def _one(kind, x, marks, arg, theta, props):
    if kind == "max_abs":
        return float(np.max(np.abs(x)))
    if kind == "max":
        return float(np.max(x))
    if kind == "min":
        return float(np.min(x))
    if kind == "mean":
        return float(np.mean(x))
    if kind == "range":
        return float(np.max(x) - np.min(x))
    if kind == "rms":
        return math.sqrt(float(np.mean(x * x)))
    if kind == "amplitude":  # sigma_a = (max - min) / 2
        return float(np.max(x) - np.min(x)) / 2
    if kind == "midrange":  # sigma_m = (max + min) / 2
        return float(np.max(x) + np.min(x)) / 2
    if kind == "goodman":
        return float(
            goodman(
                float(np.max(x) - np.min(x)) / 2,
                float(np.max(x) + np.min(x)) / 2,
                props["material"],
            )
        )
    if kind == "buckling_margin":  # critical load over the peak compression (tension > 0)
        c = -float(np.min(x))
        return critical_load(props) / c if c > 0 else math.inf
    if kind == "at":  # value at a crank angle (degrees) of the cycle, first time in the window
        period = 2 * math.pi * props.get("cycle", 1)
        a0 = theta[0]
        target = a0 + (math.radians(arg) - a0) % period
        return float(np.interp(target, theta, x))
    if kind == "order":  # amplitude of engine order k over the measured whole revolutions
        lo, hi = marks[0], marks[-1]
        xs, th = x[lo:hi], theta[lo:hi]
        return float(2.0 / len(xs) * abs(np.sum(xs * np.exp(-1j * arg * th))))
    # growth: peak of the last measured revolution over the first's
    a = np.max(np.abs(x[marks[0] : marks[1] + 1]))
    b = np.max(np.abs(x[marks[-2] : marks[-1] + 1]))
    return float(b / a) if a > 0 else float("nan")


def compute_metrics(metrics, series, marks, props=None):
    """Metrics over the measured window. A two-column output (section.stress: both outer
    fibres) gives the governing fibre's value: max, max_abs and range take the larger, min the
    smaller, goodman the smaller safety factor; the others the fibre with the smaller Goodman
    factor (with a [material]) or the larger amplitude."""
    props = props or {}
    theta = series.get("crank.angle")
    out = {}
    for m in metrics:
        kind, name, arg = parse_metric(m)
        x = series[name]
        if x.ndim == 1:
            out[m] = _one(kind, x, marks, arg, theta, props)
            continue
        vals = [_one(kind, x[:, j], marks, arg, theta, props) for j in range(x.shape[1])]
        if kind in ("max", "max_abs", "range"):
            out[m] = max(vals)
        elif kind in ("min", "goodman"):
            out[m] = min(vals)
        else:
            if "material" in props:
                key = [
                    _one("goodman", x[:, j], marks, None, theta, props) for j in range(x.shape[1])
                ]
                j = int(np.argmin(key))
            else:
                j = int(
                    np.argmax(
                        [
                            _one("amplitude", x[:, j], marks, None, theta, props)
                            for j in range(x.shape[1])
                        ]
                    )
                )
            out[m] = vals[j]
    return {k: float(v) for k, v in out.items()}


def parse_metric(text):
    """`kind(output)` or `kind(output, number)`: (kind, output, number or None)."""
    text = text.strip()
    if "(" not in text or not text.endswith(")"):
        raise ValueError(
            f"metric {text!r}: expected kind(output), kind one of {', '.join(METRIC_KINDS)}"
        )
    kind, inner = text[:-1].split("(", 1)
    kind = kind.strip()
    parts = [p.strip() for p in inner.split(",")]
    if kind not in METRIC_KINDS:
        raise ValueError(
            f"metric {text!r}: unknown kind {kind!r}; one of {', '.join(METRIC_KINDS)}"
        )
    arg = None
    if kind in ARG_KINDS:
        if len(parts) != 2:
            raise ValueError(
                f"metric {text!r}: {kind} takes an output and a number: "
                + ("at(X, crank angle in degrees)" if kind == "at" else "order(X, k)")
            )
        try:
            arg = float(parts[1])
        except ValueError:
            raise ValueError(f"metric {text!r}: {parts[1]!r} is not a number")
        if kind == "order" and not arg > 0:
            raise ValueError(f"metric {text!r}: the order must be > 0")
    elif len(parts) != 1:
        raise ValueError(f"metric {text!r}: {kind} takes one output")
    return kind, parts[0], arg


def run_chunk(fmu, chunk, job):
    """A Dask task: runs of one chunk on this process's FMU instance. `chunk`: list of
    (run_id, fmu_values, csv_values). Returns a list of result rows (dicts)."""
    runner = get_runner(fmu)
    with runner.busy:
        return _run_rows(runner, chunk, job)


def _run_rows(runner, chunk, job):
    rows = []
    metrics, record = job["metrics"], job["record"]
    for run_id, values, shown in chunk:
        t0 = time.perf_counter()
        try:
            status, message, met, rec, _ = runner.run(values, job)
        except Exception as e:  # never lose the sweep to one run
            status, message, met, rec = "exception", f"{type(e).__name__}: {e}", {}, {}
        wall = time.perf_counter() - t0
        row = {"run": run_id, **shown}
        for m in metrics:
            row[m] = met.get(m, float("nan"))
        for r in record:
            row[r] = rec.get(r, float("nan"))
        row.update(status=status, message=message.replace("\n", " "), wall_time=wall)
        rows.append(row)
    return rows
