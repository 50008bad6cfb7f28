"""Worker side: one FMU instance per process (extracted once, reused with fmi2Reset between
runs), the crank drive loop and the metrics.

Everything here is deterministic: the same run gives bit-identical metrics in any process.
"""

import ctypes
import hashlib
import math
import os
import tempfile
import threading
import time
import zipfile

import numpy as np

STATUS_NAMES = {0: "ok", 1: "warning", 2: "discard", 3: "error", 4: "fatal", 5: "pending"}

# Per process: FMU digest -> Runner (one per thread, Dask workers use one thread each by default).
_RUNNERS = {}
_LOCK = threading.Lock()


class RunFailed(Exception):
    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message


def fmu_digest(data):
    return hashlib.sha256(data).hexdigest()[:16]


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
            unzipdir = tempfile.mkdtemp(prefix=f"flexrod_sweep_{key[0]}_")
            path = os.path.join(unzipdir, "model.fmu")
            with open(path, "wb") as f:
                f.write(data)
            with zipfile.ZipFile(path) as z:
                z.extractall(unzipdir)
            runner = Runner(unzipdir)
            _RUNNERS[key] = runner
    return runner


class Runner:
    """One FMU2Slave with a capturing logger; `run(values, drive, metrics)` per run."""

    def __init__(self, unzipdir):
        from fmpy import calloc, free, read_model_description
        from fmpy.fmi2 import (
            FMU2Slave,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
        )

        self.md = read_model_description(unzipdir)
        self.vars = {v.name: v for v in self.md.modelVariables}
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
        vp, ui, sz = ctypes.c_void_p, ctypes.c_uint, ctypes.c_size_t
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
        self._setup = raw("fmi2SetupExperiment", vp, ctypes.c_int, ctypes.c_double,
                          ctypes.c_double, ctypes.c_int, ctypes.c_double)
        self._enter = raw("fmi2EnterInitializationMode", vp)
        self._exit = raw("fmi2ExitInitializationMode", vp)
        self._reset = raw("fmi2Reset", vp)

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
            return self._set_boolean(self.fmu.component, vr, 1, (ctypes.c_int * 1)(int(bool(value))))
        return self._set_integer(self.fmu.component, vr, 1, (ctypes.c_int * 1)(int(value)))

    def get(self, names):
        n = len(names)
        vrs = (ctypes.c_uint * n)(*[self.vars[x].valueReference for x in names])
        out = (ctypes.c_double * n)()
        self._check(self._get_real(self.fmu.component, vrs, n, out), "fmi2GetReal", 0)
        return list(out)

    # -- one run -------------------------------------------------------------------------

    def run(self, values, drive, metrics, record, outputs, abort):
        try:
            return self._run(values, drive, metrics, record, outputs, abort)
        except RunFailed as e:
            return e.status, e.message, {}, {}

    def _run(self, values, drive, metrics, record, outputs, abort):
        """Simulate one run. `values`: FMU variable name -> value already converted for the
        FMU (enumerations as integers). Returns (status, message, metrics dict, record dict)."""
        self.messages.clear()
        comp = self.fmu.component
        if not self.fresh:
            self._reset(comp)
        self.fresh = False
        worst = 0
        speed = float(values.get("crank.speed", drive["speed"]))
        force = values.get("slider.force")
        law = CrankLaw(drive, speed)
        dt = drive["step"]
        n_steps, n_start_measure, rev_marks = law.schedule(dt)
        t_stop = n_steps * dt
        worst = self._check(self._setup(comp, 0, 0.0, 0.0, 1, t_stop), "fmi2SetupExperiment", worst)
        for name, value in values.items():
            if self.vars[name].causality == "input":
                continue
            worst = self._check(self._set_value(name, value), f"set {name}", worst)
        worst = self._check(self._enter(comp), "fmi2EnterInitializationMode", worst)
        vr_in = (ctypes.c_uint * 2)(self.vars["crank.angle"].valueReference,
                                    self.vars["crank.speed"].valueReference)
        vr_speed = (ctypes.c_uint * 1)(self.vars["crank.speed"].valueReference)
        order = (ctypes.c_int * 1)(1)
        acc = (ctypes.c_double * 1)()
        inp = (ctypes.c_double * 2)()
        if force is not None:
            worst = self._check(self._set_value("slider.force", force), "set slider.force", worst)
        a0, w0, al0 = law(0.0)
        inp[0], inp[1] = a0, w0
        worst = self._check(self._set_real(comp, vr_in, 2, inp), "set crank inputs", worst)
        if al0 != 0.0:
            acc[0] = al0
            worst = self._check(self._set_deriv(comp, vr_speed, 1, order, acc), "set crank acceleration", worst)
        worst = self._check(self._exit(comp), "fmi2ExitInitializationMode", worst)
        rec = dict(zip(record, self.get(record))) if record else {}

        n_out = len(outputs)
        vr_out = (ctypes.c_uint * n_out)(*[self.vars[x].valueReference for x in outputs])
        n_meas = n_steps - n_start_measure + 1
        data = np.empty((n_meas, n_out))
        row = (ctypes.c_double * n_out)()
        abort_idx = [(outputs.index(k), v) for k, v in abort.items()]
        status = "ok"
        message = ""
        t = 0.0
        try:
            for k in range(n_steps):
                t = k * dt
                if k:
                    angle, w, al = law(t)
                    inp[0], inp[1] = angle, w
                    worst = self._check(self._set_real(comp, vr_in, 2, inp), "set crank inputs", worst)
                    if al != 0.0:
                        acc[0] = al
                        worst = self._check(self._set_deriv(comp, vr_speed, 1, order, acc),
                                            "set crank acceleration", worst)
                worst = self._check(self._do_step(comp, t, dt, 1), f"fmi2DoStep at t = {t:.6g} s", worst)
                j = k + 1 - n_start_measure
                if j >= 0 or abort_idx:
                    self._check(self._get_real(comp, vr_out, n_out, row), "fmi2GetReal", 0)
                    for i, limit in abort_idx:
                        x = row[i]
                        if not math.isfinite(x) or abs(x) > limit:
                            raise RunFailed("diverged", f"|{outputs[i]}| = {x:.4g} > {limit:g} at t = {(k + 1) * dt:.6g} s")
                    if j >= 0:
                        data[j] = row
        except RunFailed as e:
            return e.status, e.message, {}, rec
        if not np.all(np.isfinite(data)):
            return "diverged", "non-finite output", {}, rec
        if worst == 1:
            status = "warning"
            warn = [m for s, m in self.messages if s == 1]
            message = warn[0] if warn else "fmi2Warning"
        # Revolution boundaries inside the measured window, for growth().
        marks = [m - n_start_measure for m in rev_marks]
        series = {name: data[:, i] for i, name in enumerate(outputs)}
        if any(parse_metric(m)[1] in DERIVED for m in metrics):
            series.update(derived(series, self.get(["crank.length"])[0]))
        return status, message, compute_metrics(metrics, series, marks), rec


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

    def schedule(self, dt):
        """(number of steps, first measured step index, step indices of revolution marks)."""
        if self.kind == "constant":
            period = 2 * math.pi / abs(self.w)
            n_start = round(self.ts / dt)
            self.ts = n_start * dt  # the start ends on a communication point
            self.a = self.w / self.ts if self.ts > 0 else 0.0
            trans = max(self.drive["transient_revolutions"] * period, self.drive["min_transient_time"])
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
    "rod.axial_force": ["pinB.force_x", "pinB.force_y", "pinC.force_x", "pinC.force_y",
                        "crank.angle", "slider.position"],
}


def derived(s, r):
    bx, by = r * np.cos(s["crank.angle"]), r * np.sin(s["crank.angle"])
    ex, ey = s["slider.position"] - bx, -by
    n = np.hypot(ex, ey)
    ex, ey = ex / n, ey / n
    nb = s["pinB.force_x"] * ex + s["pinB.force_y"] * ey
    nc = -(s["pinC.force_x"] * ex + s["pinC.force_y"] * ey)
    return {"rod.axial_force": 0.5 * (nb + nc)}


METRIC_KINDS = ("max_abs", "max", "min", "mean", "range", "rms", "growth")


def compute_metrics(metrics, series, marks):
    out = {}
    for m in metrics:
        kind, name = parse_metric(m)
        x = series[name]
        if kind == "max_abs":
            v = np.max(np.abs(x))
        elif kind == "max":
            v = np.max(x)
        elif kind == "min":
            v = np.min(x)
        elif kind == "mean":
            v = np.mean(x)
        elif kind == "range":
            v = np.max(x) - np.min(x)
        elif kind == "rms":
            v = math.sqrt(np.mean(x * x))
        else:  # growth: peak of the last measured revolution over the first's
            a = np.max(np.abs(x[marks[0]:marks[1] + 1]))
            b = np.max(np.abs(x[marks[-2]:marks[-1] + 1]))
            v = b / a if a > 0 else float("nan")
        out[m] = float(v)
    return out


def parse_metric(text):
    text = text.strip()
    if "(" not in text or not text.endswith(")"):
        raise ValueError(f"metric {text!r}: expected kind(output), kind one of {', '.join(METRIC_KINDS)}")
    kind, name = text[:-1].split("(", 1)
    kind, name = kind.strip(), name.strip()
    if kind not in METRIC_KINDS:
        raise ValueError(f"metric {text!r}: unknown kind {kind!r}; one of {', '.join(METRIC_KINDS)}")
    return kind, name


def run_chunk(fmu, chunk, drive, metrics, record, outputs, abort):
    """A Dask task: runs of one chunk on this process's FMU instance. `chunk`: list of
    (run_id, fmu_values, csv_values). Returns a list of result rows (dicts)."""
    runner = get_runner(fmu)
    rows = []
    for run_id, values, shown in chunk:
        t0 = time.perf_counter()
        try:
            status, message, met, rec = runner.run(values, drive, metrics, record, outputs, abort)
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
