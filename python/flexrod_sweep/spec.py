"""The sweep spec (TOML): reading, expanding the runs, and validating every name and value
against the FMU's modelDescription before any run starts.

```toml
[fmu]
path = "../../target/fmu/FlexibleSliderCrank.fmu"   # relative to the spec file
# or: scene = "../../scenes/benchmark.toml"          # exported with cargo into target/sweep-fmu/NAME/
# scene_overrides = { "rod.model" = "segments" }      # optional edits of the scene's TOML keys

[parameters]              # FMU variable names; swept values are combined as a grid
"crank.speed" = { linspace = [50, 600, 12] }
"rod.model" = ["ffr", "segments"]                     # list (enumeration items by name)
"rod.damping_ratio" = 0.02                            # fixed value
"slider.mass" = { range = [0.0, 0.5] }                # Latin hypercube dimension

[sampling]                # only with { range = ... } parameters
samples = 20              # Latin hypercube points, combined with the grid
seed = 1

[drive]
kind = "constant"         # constant speed after a start; or "ramp"
speed = 150.0             # used when crank.speed is not swept
start_time = 0.02         # s of uniform acceleration from rest (0 = abrupt start)
transient_revolutions = 3
min_transient_time = 0.0  # s; the discarded span is the longer of the two
measure_revolutions = 2
step = 1e-4               # communication step, s
# ramp: speed_from, speed_to, duration (metrics over the run after min_transient_time)
gas = { peak = 38e3, angle = 15.0, width = 20.0, cycle = 2 }  # optional gas-force pulse on
# slider.force: N, degrees after crank angle 0, degrees, revolutions per cycle; sweep its keys
# as parameters "gas.peak" etc.

[metrics]                 # kinds: max_abs max min mean range rms growth amplitude midrange
                          # goodman buckling_margin at(X, deg) order(X, k); docs/sweeps.md
list = ["max_abs(rod.deflection_rel)", "mean(crank.torque)", "range(pinB.force_x)"]
record = ["rod.frequency[1]"]        # calculated parameters read after initialization
abort = { "rod.deflection_rel" = 0.5 }   # a run stops as "diverged" beyond this |value|

[run]
timeout = 30.0            # s of wall time per run: a run past it ends as status "timeout"

[section]                 # the critical section, for the section.stress outputs (midpoint forces)
area = 2.16e-4            # m2
area_moment = 1.613e-8    # m4, bending in the mechanism's plane (the FMU's rod.area_moment)
fibre_distance = 0.012    # m

[material]                # for goodman(...) and Johnson's parabola in buckling_margin(...)
endurance_strength = 3.0e8   # S_e, Pa (fully corrected)
ultimate_strength = 8.5e8    # S_u, Pa
yield_strength = 6.0e8       # S_y, Pa (optional)

[buckling]                # for buckling_margin(...): the column; defaults from the FMU's parameters
area_moment = 4.0e-9      # m4: the smaller of the in-plane and out-of-plane moments of area
# area, length, youngs_modulus: default rod.area, rod.length, rod.youngs_modulus of the FMU
end_factor = 1.0          # K, effective length K L (1: pinned-pinned)

[plots]
resonance = { x = "crank.speed", metric = "max_abs(rod.deflection_rel)", frequency = "rod.frequency[1]", harmonics = [2, 3, 4, 5, 6] }
heatmap = { x = "crank.speed", y = "rod.damping_ratio", metric = "growth(rod.deflection_rel)" }
# resonance: normalized = true adds metric / Omega^2; heatmap: log = true, contour = 0.05 or
# [2.0, 3.0], vmin, vmax (colour limits), cmap, title, file; frequency and harmonics mark
# omega_1 / k on a crank-speed axis
```
"""

import hashlib
import itertools
import json
import math
import tomllib
from pathlib import Path

import numpy as np

from .runner import DERIVED, DERIVED_PROPS, parse_metric


class SpecError(Exception):
    """A spec that cannot run: raised before any run starts."""


DRIVE_DEFAULTS = {
    "kind": "constant",
    "speed": 150.0,
    "start_time": 0.0,
    "transient_revolutions": 2,
    "min_transient_time": 0.0,
    "measure_revolutions": 2,
    "step": 1e-4,
}


GAS_KEYS = ("peak", "angle", "width", "cycle")
TABLES = {
    "fmu",
    "parameters",
    "sampling",
    "drive",
    "metrics",
    "plots",
    "name",
    "run",
    "section",
    "material",
    "buckling",
}


def run_id(shown):
    """The id of a run: a digest of its parameter values (names sorted), so that a run keeps its
    id when the grid grows or is reordered."""
    key = json.dumps({k: shown[k] for k in sorted(shown)}, sort_keys=True)
    return hashlib.sha256(key.encode()).hexdigest()[:12]


def as_spec(spec, base=None):
    """A Spec from a TOML path, a dict of the same structure (relative paths against `base`,
    default the current directory) or a Spec."""
    if isinstance(spec, Spec):
        return spec
    if isinstance(spec, dict):
        return Spec(spec, Path(base or ".").resolve(), None)
    return load(spec)


def load(path):
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise SpecError(f"{path}: cannot read the spec: {e}")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SpecError(f"{path}: not valid TOML: {e}")
    spec = Spec(raw, path.parent.resolve(), text)
    spec.path = path.resolve()
    return spec


class Spec:
    def __init__(self, raw, base, text=""):
        self.raw = raw
        self.base = base
        self.text = text
        self.path = None
        known = TABLES
        unknown = set(raw) - known
        if unknown:
            raise SpecError(f"unknown table(s) {sorted(unknown)}; allowed: {sorted(known)}")
        fmu = raw.get("fmu", {})
        if ("path" in fmu) == ("scene" in fmu):
            raise SpecError('[fmu] needs exactly one of path = "X.fmu" or scene = "S.toml"')
        self.fmu_path = (base / fmu["path"]).resolve() if "path" in fmu else None
        self.scene = (base / fmu["scene"]).resolve() if "scene" in fmu else None
        self.scene_overrides = fmu.get("scene_overrides", {})
        self.name = raw.get("name", "sweep")

        drive = dict(DRIVE_DEFAULTS)
        extra = (
            set(raw.get("drive", {}))
            - set(DRIVE_DEFAULTS)
            - {"speed_from", "speed_to", "duration", "gas"}
        )
        if extra:
            raise SpecError(f"[drive]: unknown key(s) {sorted(extra)}")
        drive.update(raw.get("drive", {}))
        if drive["kind"] not in ("constant", "ramp"):
            raise SpecError(f'[drive] kind = {drive["kind"]!r}: one of "constant", "ramp"')
        if drive["kind"] == "ramp":
            for k in ("speed_from", "speed_to", "duration"):
                if k not in drive:
                    raise SpecError(f'[drive] kind = "ramp" needs {k}')
            if not drive["duration"] > 0:
                raise SpecError("[drive] duration must be > 0")
        for k in ("step",):
            if not (isinstance(drive[k], (int, float)) and drive[k] > 0):
                raise SpecError(f"[drive] {k} = {drive[k]!r} must be > 0")
        for k in ("start_time", "min_transient_time", "transient_revolutions"):
            if not (isinstance(drive[k], (int, float)) and drive[k] >= 0):
                raise SpecError(f"[drive] {k} = {drive[k]!r} must be >= 0")
        if not (
            isinstance(drive["measure_revolutions"], int) and drive["measure_revolutions"] >= 1
        ):
            raise SpecError("[drive] measure_revolutions must be an integer >= 1")
        self.gas = drive.pop("gas", None)
        if self.gas is not None:
            bad = set(self.gas) - set(GAS_KEYS)
            if bad or "peak" not in self.gas and "gas.peak" not in raw.get("parameters", {}):
                raise SpecError(
                    f"[drive] gas = {self.gas!r}: keys {', '.join(GAS_KEYS)} (peak required)"
                )
        self.drive = drive
        run = raw.get("run", {})
        if set(run) - {"timeout"}:
            raise SpecError(
                f"[run]: unknown key(s) {sorted(set(run) - {'timeout'})}; allowed: timeout"
            )
        self.timeout = run.get("timeout")
        if self.timeout is not None and not (
            isinstance(self.timeout, (int, float)) and self.timeout > 0
        ):
            raise SpecError(f"[run] timeout = {self.timeout!r}: seconds of wall time per run, > 0")
        self.section = dict(raw.get("section", {}))
        self.material = dict(raw.get("material", {}))
        self.buckling = dict(raw.get("buckling", {}))
        for table, keys in (
            ("section", {"area", "area_moment", "fibre_distance"}),
            ("material", {"endurance_strength", "ultimate_strength", "yield_strength"}),
            ("buckling", {"area", "area_moment", "length", "youngs_modulus", "end_factor"}),
        ):
            d = getattr(self, table)
            if set(d) - keys:
                raise SpecError(
                    f"[{table}]: unknown key(s) {sorted(set(d) - keys)}; allowed: {sorted(keys)}"
                )
            for k, v in d.items():
                if not (isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0):
                    raise SpecError(f"[{table}] {k} = {v!r}: must be a number > 0")

        met = raw.get("metrics", {})
        self.metrics = list(met.get("list", ["max_abs(rod.deflection_rel)"]))
        if not self.metrics:
            raise SpecError("[metrics] list is empty: nothing to compute")
        for m in self.metrics:
            try:
                parse_metric(m)
            except ValueError as e:
                raise SpecError(f"[metrics] {e}")
        self.record = list(met.get("record", ["rod.frequency[1]"]))
        self.abort = dict(met.get("abort", {}))
        self.plots = raw.get("plots", {})
        self.params = raw.get("parameters", {})
        if not self.params:
            raise SpecError("[parameters] is empty: nothing to sweep")
        self.sampling = raw.get("sampling", {})

    # -- expansion -------------------------------------------------------------------------

    def axes(self):
        """(grid axes: name -> list of values, LHS ranges: name -> (lo, hi))."""
        grid, ranges = {}, {}
        for name, spec in self.params.items():
            if isinstance(spec, dict):
                keys = set(spec)
                if keys == {"linspace"}:
                    a, b, n = spec["linspace"]
                    if int(n) < 1:
                        raise SpecError(
                            f"parameter {name!r}: empty grid (linspace with {n} points)"
                        )
                    grid[name] = [float(x) for x in np.linspace(float(a), float(b), int(n))]
                elif keys == {"logspace"}:
                    a, b, n = spec["logspace"]
                    if int(n) < 1:
                        raise SpecError(
                            f"parameter {name!r}: empty grid (logspace with {n} points)"
                        )
                    if not (a > 0 and b > 0):
                        raise SpecError(f"parameter {name!r}: logspace bounds must be > 0")
                    grid[name] = [float(x) for x in np.geomspace(float(a), float(b), int(n))]
                elif keys == {"range"}:
                    lo, hi = spec["range"]
                    if not lo <= hi:
                        raise SpecError(f"parameter {name!r}: empty range [{lo}, {hi}]")
                    ranges[name] = (float(lo), float(hi))
                else:
                    raise SpecError(
                        f"parameter {name!r}: expected a value, a list, "
                        f"{{linspace = [a, b, n]}}, {{logspace = [a, b, n]}} or {{range = [lo, hi]}}; got {spec!r}"
                    )
            elif isinstance(spec, list):
                if not spec:
                    raise SpecError(f"parameter {name!r}: empty grid (empty list)")
                grid[name] = list(spec)
            else:
                grid[name] = [spec]
        if ranges and int(self.sampling.get("samples", 0)) < 1:
            raise SpecError(
                f"{sorted(ranges)} given as {{range = ...}}: [sampling] samples must be >= 1 (empty Latin hypercube)"
            )
        if self.sampling and not ranges:
            raise SpecError("[sampling] given but no parameter is a {range = [lo, hi]}")
        return grid, ranges

    def runs(self):
        """The list of runs: dicts name -> value (spec values, enumerations by name), in a
        fixed order (grid in spec order, last name fastest; LHS points inside each grid point)."""
        grid, ranges = self.axes()
        lhs = [{}]
        if ranges:
            n = int(self.sampling["samples"])
            rng = np.random.default_rng(int(self.sampling.get("seed", 0)))
            cols = {}
            for name, (lo, hi) in ranges.items():
                u = (rng.permutation(n) + rng.random(n)) / n
                cols[name] = [float(lo + (hi - lo) * x) for x in u]
            lhs = [{name: cols[name][i] for name in ranges} for i in range(n)]
        names = list(grid)
        runs = []
        for combo in itertools.product(*[grid[k] for k in names]):
            for point in lhs:
                runs.append({**dict(zip(names, combo)), **point})
        return runs

    def swept_names(self):
        return list(self.params)

    def definition_hash(self):
        """Hash of what determines a run's result besides its values: drive, metrics and their
        section, material and column properties (the FMU is recorded apart)."""
        d = {
            "drive": self.drive,
            "metrics": self.metrics,
            "record": self.record,
            "abort": self.abort,
        }
        for k in ("gas", "section", "material", "buckling"):
            if getattr(self, k):
                d[k] = getattr(self, k)
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]

    # -- validation against the model description -------------------------------------------

    def validate(self, md):
        """Check every name and value against the FMU; returns the runs converted for the FMU:
        list of (fmu_values, shown_values). Also resolves the [buckling] column's defaults from
        the FMU's parameters (self.props)."""
        variables = {v.name: v for v in md.modelVariables}
        types = {t.name: t for t in md.typeDefinitions}
        grid, ranges = self.axes()
        for name in self.params:
            if name.startswith("gas."):
                if self.gas is None:
                    raise SpecError(
                        f"parameter {name!r}: needs [drive] gas = {{...}} (the gas-force pulse)"
                    )
                if name[4:] not in GAS_KEYS:
                    raise SpecError(
                        f"parameter {name!r}: gas keys are {', '.join('gas.' + k for k in GAS_KEYS)}"
                    )
                for value in grid.get(name, list(ranges.get(name, ()))):
                    if (
                        isinstance(value, bool)
                        or not isinstance(value, (int, float))
                        or not math.isfinite(value)
                    ):
                        raise SpecError(f"{name} = {value!r}: expected a number")
                continue
            if name not in variables:
                close = [n for n in variables if name.split(".")[-1] in n]
                hint = f"; did you mean {', '.join(close[:4])}?" if close else ""
                raise SpecError(
                    f"unknown variable {name!r}: not in the FMU's modelDescription{hint}"
                )
            v = variables[name]
            if v.causality not in ("parameter", "input"):
                raise SpecError(
                    f"{name!r} is a {v.causality} ({v.variability}): only parameters and inputs can be swept"
                )
            if name in ("crank.angle",):
                raise SpecError("crank.angle is driven by [drive]; sweep crank.speed instead")
            if name == "slider.force" and self.gas is not None:
                raise SpecError("slider.force is driven by [drive] gas; sweep gas.peak instead")
            values = grid.get(name, list(ranges.get(name, ())))
            for value in values:
                self._check_value(v, types, value)
        if self.gas is not None and "slider.force" not in variables:
            raise SpecError(
                "[drive] gas: the FMU has no slider.force input (scene [outputs] slider_force)"
            )
        start = {v.name: _num(v.start) for v in md.modelVariables if v.type == "Real"}
        self.props = {}
        if self.section:
            self.props["section"] = dict(self.section)
        if self.material:
            self.props["material"] = dict(self.material)
        for m in self.metrics:
            kind, out, _ = parse_metric(m)
            if kind == "goodman":
                missing = [
                    k for k in ("endurance_strength", "ultimate_strength") if k not in self.material
                ]
                if missing:
                    raise SpecError(f"metric {m!r}: [material] needs {', '.join(missing)} (Pa)")
            if kind == "buckling_margin":
                b = dict(self.buckling)
                for key, var in (
                    ("area", "rod.area"),
                    ("area_moment", "rod.area_moment"),
                    ("length", "rod.length"),
                    ("youngs_modulus", "rod.youngs_modulus"),
                ):
                    if key not in b:
                        if start.get(var) is None:
                            raise SpecError(
                                f"metric {m!r}: [buckling] {key} not given and the FMU has no {var}"
                            )
                        b[key] = start[var]
                b.setdefault("end_factor", 1.0)
                self.props["buckling"] = b
            if out in DERIVED:
                missing = [x for x in DERIVED[out] + ["crank.length"] if x not in variables]
                if missing:
                    raise SpecError(f"metric {m!r}: the FMU lacks {missing}, which {out} needs")
                need = [k for k in DERIVED_PROPS.get(out, []) if k not in self.section]
                if need:
                    raise SpecError(f"metric {m!r}: {out} needs [section] {', '.join(need)}")
                continue
            if out == "slider.force" and self.gas is not None:
                continue
            if out not in variables or variables[out].causality != "output":
                outs = [n for n, v in variables.items() if v.causality == "output"] + list(DERIVED)
                raise SpecError(
                    f"metric {m!r}: {out!r} is not an output of the FMU; outputs: {', '.join(outs)}"
                )
        for r in self.record:
            if r not in variables:
                raise SpecError(f"[metrics] record: unknown variable {r!r}")
            if variables[r].type != "Real":
                raise SpecError(f"[metrics] record: {r!r} is not a Real")
        for out, lim in self.abort.items():
            if out not in variables or variables[out].causality != "output":
                raise SpecError(f"[metrics] abort: {out!r} is not an output of the FMU")
            if not lim > 0:
                raise SpecError(f"[metrics] abort: limit for {out!r} must be > 0")
        if self.drive["kind"] == "constant" and "crank.speed" not in self.params:
            if self.drive["speed"] == 0:
                raise SpecError(
                    '[drive] speed = 0 with kind = "constant": no revolution to measure'
                )
        out = []
        for run in self.runs():
            fmu_values = {
                n: (float(x) if n.startswith("gas.") else self._convert(variables[n], types, x))
                for n, x in run.items()
            }
            out.append((fmu_values, run))
        if self.drive["kind"] == "constant":
            for fmu_values, run in out:
                if fmu_values.get("crank.speed", self.drive["speed"]) == 0:
                    raise SpecError(f"crank.speed = 0 in run {run}: no revolution to measure")
        return out

    def outputs(self):
        """The FMU outputs the metrics and abort limits read."""
        outs = []
        for m in self.metrics:
            o = parse_metric(m)[1]
            if o == "slider.force" and self.gas is not None:
                continue
            for x in DERIVED.get(o, [o]):
                if x not in outs and x != "crank.angle":
                    outs.append(x)
        for o in self.abort:
            if o not in outs:
                outs.append(o)
        return outs

    def job(self):
        """What a worker needs to run and measure a run (after validate)."""
        return {
            "drive": self.drive,
            "metrics": self.metrics,
            "record": self.record,
            "outputs": self.outputs(),
            "abort": self.abort,
            "timeout": self.timeout,
            "gas": self.gas,
            "props": {
                **getattr(self, "props", {}),
                "cycle": float(self.gas.get("cycle", 2)) if self.gas else 1.0,
            },
        }

    @staticmethod
    def _enum_items(v, types):
        t = types.get(v.declaredType.name) if v.declaredType is not None else None
        return {item.name: int(item.value) for item in (t.items if t is not None else [])}

    def _check_value(self, v, types, value):
        name = v.name
        if v.type == "Enumeration":
            items = self._enum_items(v, types)
            if isinstance(value, str):
                if value not in items:
                    raise SpecError(
                        f"{name} = {value!r}: not an item of {v.declaredType.name}; allowed: {', '.join(items)}"
                    )
                return
            if not isinstance(value, int) or value not in items.values():
                raise SpecError(f"{name} = {value!r}: allowed items {items}")
            return
        if v.type == "Boolean":
            if not isinstance(value, bool):
                raise SpecError(f"{name} = {value!r}: expected true or false")
            return
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SpecError(f"{name} = {value!r}: expected a number ({v.type})")
        if not math.isfinite(value):
            raise SpecError(f"{name} = {value!r}: not finite")
        if v.type == "Integer" and value != int(value):
            raise SpecError(f"{name} = {value!r}: expected an integer")
        lo = _num(
            v.min
            if v.min is not None
            else (v.declaredType.min if v.declaredType is not None else None)
        )
        hi = _num(
            v.max
            if v.max is not None
            else (v.declaredType.max if v.declaredType is not None else None)
        )
        if lo is not None and value < lo or hi is not None and value > hi:
            raise SpecError(
                f"{name} = {value!r}: outside its range [{lo if lo is not None else '-inf'}, "
                f"{hi if hi is not None else 'inf'}] declared by the FMU"
            )

    def _convert(self, v, types, value):
        if v.type == "Enumeration" and isinstance(value, str):
            return self._enum_items(v, types)[value]
        if v.type in ("Integer", "Enumeration"):
            return int(value)
        if v.type == "Boolean":
            return bool(value)
        return float(value)


def _num(x):
    if x is None:
        return None
    try:
        return float(x)
    except (TypeError, ValueError):
        return None
