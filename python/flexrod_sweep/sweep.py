"""Orchestration: FMU (given or exported from a scene), validation, the runs in chunks on Dask
(a LocalCluster, a scheduler address, or in this process), results.csv and results.parquet
(resumable), time series of chosen runs, charts, and the regeneration of committed studies."""

import csv
import hashlib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time
import zipfile
from pathlib import Path

from . import runner as _runner
from .spec import SpecError, as_spec, run_id

META = "sweep.json"
# Statuses of the infrastructure, not of the model: a resumed sweep runs them again.
RERUN = ("exception",)
# Files of a study that `regenerate` makes anew.
PRODUCTS = (
    "results.csv",
    "results.parquet",
    META,
    "last_run.json",
    "spec.toml",
    "spec.json",
    "modelDescription.xml",
)


def find_root(start):
    for p in [Path(start).resolve(), *Path(start).resolve().parents]:
        if (p / "Cargo.toml").exists() and (p / "fmu").is_dir():
            return p
    raise SpecError(f"[fmu] scene: no flexrod workspace (Cargo.toml with fmu/) above {start}")


def export_scene(spec):
    """`cargo run --release -p fmu -- SCENE --out ROOT/target/sweep-fmu/NAME` (with the spec's
    scene overrides written into a copy of the scene); returns the .fmu path."""
    scene = spec.scene
    if not scene.exists():
        raise SpecError(f"[fmu] scene {scene} does not exist")
    root = find_root(spec.scene.parent)
    fmu_dir = root / "target" / "sweep-fmu" / re.sub(r"[^A-Za-z0-9_.-]", "_", spec.name)
    fmu_dir.mkdir(parents=True, exist_ok=True)
    if spec.scene_overrides:
        text = scene.read_text()
        for key, value in spec.scene_overrides.items():
            table, k = key.rsplit(".", 1)
            val = (
                json.dumps(value)
                if isinstance(value, str)
                else repr(value).lower()
                if isinstance(value, bool)
                else repr(value)
            )
            pat = re.compile(
                rf"(\[{re.escape(table)}\][^\[]*?^{re.escape(k)}\s*=\s*)[^\n#]*", re.M | re.S
            )
            text, n = pat.subn(lambda m: m.group(1) + val, text, count=1)
            if n == 0:
                raise SpecError(
                    f"[fmu] scene_overrides: no key {k!r} in table [{table}] of {scene}"
                )
        scene = fmu_dir / "scene.toml"
        scene.write_text(text)
    cmd = ["cargo", "run", "--release", "-q", "-p", "fmu", "--", str(scene), "--out", str(fmu_dir)]
    res = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
    if res.returncode != 0:
        raise SpecError(f"exporting {scene} failed:\n{res.stdout}\n{res.stderr}")
    for line in res.stdout.splitlines():
        if line.startswith("wrote ") and ".fmu" in line and "fmi3" not in line:
            return Path(line.split(" ")[1])
    raise SpecError(f"the packager reported no .fmu:\n{res.stdout}")


def model_digest(fmu_path):
    """Digest of what determines the FMU's results: the contents of its modelDescription.xml,
    resources and binaries (not the archive's time stamps)."""
    h = hashlib.sha256()
    with zipfile.ZipFile(fmu_path) as z:
        for name in sorted(z.namelist()):
            if name.endswith("/") or not name.startswith(
                ("modelDescription.xml", "resources/", "binaries/")
            ):
                continue
            h.update(name.encode() + b"\0")
            h.update(hashlib.sha256(z.read(name)).digest())
    return h.hexdigest()[:16]


def columns(spec):
    return [
        "run",
        "index",
        *spec.swept_names(),
        *spec.metrics,
        *spec.record,
        "status",
        "message",
        "wall_time",
    ]


def fmt(x):
    if isinstance(x, float):
        return repr(x)
    return str(x)


def read_results(path):
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def make_chunks(todo, n_chunks):
    n_chunks = max(1, min(n_chunks, len(todo)))
    # Interleaved so that every chunk gets a mix of cheap and dear runs.
    return [todo[i::n_chunks] for i in range(n_chunks)]


def units_of(md, spec):
    """Unit of every column (from the model description; metrics: their output's unit, `1` for
    ratios)."""
    from .runner import DERIVED_UNITS, DIMENSIONLESS_KINDS, parse_metric

    unit = {}
    for v in md.modelVariables:
        u = v.unit or (
            getattr(v.declaredType, "unit", None) if v.declaredType is not None else None
        )
        # A Real without a unit is a ratio ("1"); integers and enumerations have none.
        unit[v.name] = u or ("1" if v.type == "Real" else "")
    unit.update(DERIVED_UNITS)
    unit.update({"gas.peak": "N", "gas.angle": "deg", "gas.width": "deg", "gas.cycle": "rev"})
    out = {n: unit.get(n, "") for n in spec.swept_names()}
    for m in spec.metrics:
        kind, name, _ = parse_metric(m)
        out[m] = "1" if kind in DIMENSIONLESS_KINDS else unit.get(name, "")
    for r in spec.record:
        out[r] = unit.get(r, "")
    out["wall_time"] = "s"
    return out


def to_frame(rows, spec, info):
    """The results as a pandas DataFrame: parameters, metrics, recorded values and wall time
    numeric (enumerations by item name), run id, status and message text; `info` in `.attrs`."""
    import pandas as pd

    cols = columns(spec)
    df = pd.DataFrame([{c: r.get(c, "") for c in cols} for r in rows], columns=cols)
    for c in spec.swept_names():
        vals = df[c]
        if len(vals) and set(vals) <= {"True", "False"}:
            df[c] = vals == "True"
            continue
        num = pd.to_numeric(vals, errors="coerce")
        if not num.isna().any() or len(vals) == 0:
            df[c] = num
    for c in [*spec.metrics, *spec.record, "wall_time"]:
        df[c] = pd.to_numeric(df[c].replace("", "nan"), errors="coerce").astype("float64")
    df["index"] = pd.to_numeric(df["index"].replace("", None), errors="coerce").astype("Int64")
    for c in ("run", "status", "message"):
        df[c] = df[c].astype(str)
    df.attrs.update(json.loads(json.dumps(info, default=str)))
    return df


def run_sweep(
    spec,
    out,
    scheduler=None,
    workers=None,
    chunks_per_worker=4,
    progress=True,
    plots=True,
    retry_failed=False,
    series=None,
    only=None,
    fmu=None,
):
    """Run (or resume) a sweep; returns the results as a pandas DataFrame.

    spec: a TOML path, a dict of the same structure (relative paths against the current
    directory) or a Spec. out: the results folder (results.csv, results.parquet, charts).
    scheduler: a dask.distributed address; workers: LocalCluster worker processes (default the
    CPU count; 0: in this process). Runs already in out/results.csv are kept, except those of
    status `exception` (the infrastructure's failures: a lost worker); retry_failed=True also
    reruns every run whose status is not ok/warning. series: run ids or dicts of parameter values
    of runs whose time series (every FMU output at every communication point) to write to
    out/series/RUN.parquet (see `load_series`). only: run ids to run (the others are skipped).
    fmu: an FMU path instead of the spec's [fmu]. The DataFrame's `.attrs` hold the run
    information (runs, ran, skipped, elapsed, workers, fmu digests, units, series files).
    Ctrl-C (KeyboardInterrupt) keeps the finished rows in results.csv/parquet and re-raises."""
    from fmpy import read_model_description

    spec_obj = as_spec(spec)
    out = Path(out)
    if fmu is not None:
        fmu_path = Path(fmu)
    elif spec_obj.fmu_path is not None:
        fmu_path = spec_obj.fmu_path
    else:
        fmu_path = export_scene(spec_obj)
    if not Path(fmu_path).exists():
        raise SpecError(
            f"[fmu] path {fmu_path} does not exist (build it: cargo run --release -p fmu)"
        )
    md = read_model_description(str(fmu_path))
    runs = spec_obj.validate(md)  # every check before any run
    out.mkdir(parents=True, exist_ok=True)
    fmu_bytes = Path(fmu_path).read_bytes()
    digest = _runner.fmu_digest(fmu_bytes)

    meta_path = out / META
    meta = {
        "definition": spec_obj.definition_hash(),
        "fmu_model_digest": model_digest(fmu_path),
        "columns": columns(spec_obj),
    }
    results_path = out / "results.csv"
    if meta_path.exists() and results_path.exists():
        old = json.loads(meta_path.read_text())
        old_cmp = {k: old.get(k) for k in meta}
        if old_cmp != meta:
            raise SpecError(
                f"{out} holds results of another FMU, drive, metric set or columns "
                f"({old_cmp} vs {meta}); choose another --out or delete it"
            )
    meta.update(
        fmu_guid=md.guid,
        fmu_file=os.path.relpath(Path(fmu_path).resolve(), out.resolve()),
        fmu_sha256=digest,
        model=md.modelName,
        name=spec_obj.name,
    )
    if spec_obj.path is not None:
        meta["spec"] = os.path.relpath(spec_obj.path, out.resolve())
        shutil.copyfile(spec_obj.path, out / "spec.toml")
    else:
        (out / "spec.json").write_text(json.dumps(spec_obj.raw, indent=1, default=str))
    meta_path.write_text(json.dumps(meta, indent=1) + "\n")
    with zipfile.ZipFile(fmu_path) as z:  # the FMU's description, for the record and the analysis
        (out / "modelDescription.xml").write_bytes(z.read("modelDescription.xml"))

    # Existing rows by run id (the last row of an id wins); drop those to rerun.
    existing = {}
    for row in read_results(results_path):
        existing[row["run"]] = row
    keep = {
        rid: r
        for rid, r in existing.items()
        if r["status"] not in RERUN and (not retry_failed or r["status"] in ("ok", "warning"))
    }
    ids = []
    todo = []
    wanted = set(only) if only is not None else None
    for index, (fmu_values, shown) in enumerate(runs):
        rid = run_id(shown)
        ids.append(rid)
        text = {k: fmt(v) for k, v in shown.items()}
        if rid in keep:
            keep[rid]["index"] = str(index)
            continue
        if wanted is not None and rid not in wanted:
            continue
        todo.append((rid, fmu_values, {"index": index, **text}))
    cols = columns(spec_obj)
    order = {rid: i for i, rid in enumerate(ids)}
    _write(results_path, cols, keep.values(), order)

    job = spec_obj.job()
    info = {
        "runs": len(runs),
        "skipped": len(runs) - len(todo),
        "ran": len(todo),
        "fmu_guid": md.guid,
        "fmu_model_digest": meta["fmu_model_digest"],
    }
    t0 = time.perf_counter()
    interrupted = False
    try:
        if todo:
            if workers == 0 and scheduler is None:
                _serial(fmu_bytes, todo, job, results_path, cols, progress)
            else:
                _dask(
                    fmu_bytes,
                    todo,
                    job,
                    results_path,
                    cols,
                    progress,
                    scheduler,
                    workers,
                    chunks_per_worker,
                    info,
                )
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        info["elapsed"] = time.perf_counter() - t0
        rows = _finish(results_path, cols, order)
        info["interrupted"] = interrupted
        info["units"] = units_of(md, spec_obj)
        df = to_frame(rows, spec_obj, info)
        _write_parquet(df, out / "results.parquet")
        if interrupted:
            info["done_rows"] = len(rows)
            (out / "last_run.json").write_text(json.dumps(info, indent=1, default=str))
    if series:
        info["series"] = write_series(fmu_bytes, spec_obj, runs, ids, series, out)
        df.attrs["series"] = info["series"]
    if plots:
        from .plots import make_plots

        info["plots"] = [str(p) for p in make_plots(spec_obj, rows, out, info["units"])]
        df.attrs["plots"] = info["plots"]
    (out / "last_run.json").write_text(
        json.dumps({k: v for k, v in info.items() if k != "units"}, indent=1, default=str) + "\n"
    )
    return df


def _write(path, cols, rows, order):
    rows = sorted(rows, key=lambda r: (order.get(r["run"], math.inf), r["run"]))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            if r["run"] not in order:
                r = {**r, "index": ""}
            w.writerow({c: r.get(c, "") for c in cols})


def _finish(results_path, cols, order):
    """Rewrite results.csv sorted in the spec's order, one row per run id (the last wins)."""
    rows = {}
    for r in read_results(results_path):
        rows[r["run"]] = r
    _write(results_path, cols, rows.values(), order)
    return read_results(results_path)


def _write_parquet(df, path):
    tmp = path.with_suffix(".parquet.tmp")
    df.to_parquet(tmp, index=False)
    os.replace(tmp, path)


def write_series(fmu_bytes, spec, runs, ids, selectors, out):
    """Rerun the chosen runs in this process, keeping every output at every communication
    point (transient included); writes out/series/RUN.parquet; returns {run id: path}."""
    import pandas as pd

    chosen = []
    for sel in selectors:
        if isinstance(sel, str):
            if sel not in ids:
                raise SpecError(f"series: no run {sel!r} in the spec")
            chosen.append(ids.index(sel))
            continue
        match = [
            i
            for i, (_, shown) in enumerate(runs)
            if all(_same(shown.get(k), v) for k, v in sel.items())
        ]
        if not match:
            raise SpecError(f"series: no run of the spec has {sel}")
        chosen += match
    runner = _runner.get_runner(fmu_bytes)
    job = spec.job()
    folder = out / "series"
    folder.mkdir(exist_ok=True)
    written = {}
    try:
        for i in dict.fromkeys(chosen):
            values, shown = runs[i]
            status, message, _, _, cols = runner.run(values, job, series=True)
            df = pd.DataFrame(cols)
            df.attrs.update(
                run=ids[i], status=status, message=message, parameters=json.loads(json.dumps(shown))
            )
            path = folder / f"{ids[i]}.parquet"
            df.to_parquet(path, index=False)
            written[ids[i]] = str(path)
    finally:
        _runner.release(_runner.fmu_digest(fmu_bytes))
    return written


def load_series(out, run):
    """The time series of run `run` written by run_sweep(..., series=[...]): a DataFrame with
    time, crank.angle and every FMU output (and slider.force with a gas force)."""
    import pandas as pd

    return pd.read_parquet(Path(out) / "series" / f"{run}.parquet")


def _same(a, b):
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=1e-15)
    return a == b


def _append(results_path, cols, rows):
    with open(results_path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        for r in rows:
            w.writerow({c: fmt(r.get(c, "")) for c in cols})
        f.flush()
        os.fsync(f.fileno())


def _bar(total, progress):
    from tqdm import tqdm

    return tqdm(total=total, unit="run", disable=not progress, file=sys.stderr, smoothing=0.1)


def _serial(fmu_bytes, todo, job, results_path, cols, progress):
    try:
        with _bar(len(todo), progress) as bar:
            runner = _runner.get_runner(fmu_bytes)
            for item in todo:
                rows = _runner._run_rows(runner, [item], job)
                _append(results_path, cols, rows)
                bar.update(1)
    finally:
        _runner.release(_runner.fmu_digest(fmu_bytes))


def _ignore_sigint():
    """On a LocalCluster worker: Ctrl-C goes to the whole process group; the client stops the
    workers itself."""
    import signal

    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread
        pass


DISTRIBUTED_LOGGERS = (
    "distributed",
    "distributed.worker",
    "distributed.nanny",
    "distributed.scheduler",
    "distributed.core",
)


def _quiet_distributed_logs():
    """In a worker process of our LocalCluster, at shutdown: Dask's own loggers to CRITICAL, so
    that a worker whose scheduler is already gone does not print heartbeat tracebacks."""
    import logging

    for name in DISTRIBUTED_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL)


def _dask(fmu_bytes, todo, job, results_path, cols, progress, scheduler, workers, cpw, info):
    import logging

    from dask.distributed import Client, LocalCluster, as_completed

    quiet = [logging.getLogger(n) for n in DISTRIBUTED_LOGGERS]
    cluster = None
    t_up = time.perf_counter()
    if scheduler is None:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address="127.0.0.1:0",
            host="127.0.0.1",
        )
        client = Client(cluster)
    else:
        client = Client(scheduler)
    digest = _runner.fmu_digest(fmu_bytes)
    futures = []
    try:
        if cluster is not None:
            client.run(_ignore_sigint)
        services = client.scheduler_info().get("services", {})
        link = client.dashboard_link if "dashboard" in services else None
        info["dashboard"] = link
        try:
            import bokeh  # noqa: F401

            note = ""
        except ImportError:
            note = " (its charts need the bokeh package: pip install bokeh)"
        print(
            f"Dask dashboard: {link}{note}"
            if link
            else "Dask dashboard: not served by the scheduler",
            file=sys.stderr,
        )
        n_workers = max(1, len(client.scheduler_info()["workers"]))
        info["workers"] = n_workers
        # The FMU goes to every worker once (works across machines: no shared file system).
        fmu_future = client.scatter(fmu_bytes, broadcast=True)
        info["startup"] = time.perf_counter() - t_up
        # Chunks of about 10 runs keep the progress bar moving; the FMU still loads once per
        # worker (the instance is cached in the worker process).
        chunks = make_chunks(todo, max(n_workers * cpw, math.ceil(len(todo) / 10)))
        futures = [
            client.submit(_runner.run_chunk, fmu_future, chunk, job, pure=False) for chunk in chunks
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        with _bar(len(todo), progress) as bar:
            for fut in as_completed(futures):
                try:
                    rows = fut.result()
                except Exception as e:  # a lost worker or chunk: its runs become rows too
                    rows = [
                        {
                            "run": rid,
                            **shown,
                            "status": "exception",
                            "message": f"chunk failed: {type(e).__name__}: {e}",
                            "wall_time": float("nan"),
                        }
                        for rid, _, shown in chunks[index[fut.key]]
                    ]
                _append(results_path, cols, rows)
                bar.update(len(rows))
    finally:
        # Closing a LocalCluster can log heartbeat errors of workers already gone: noise.
        levels = [q.level for q in quiet]
        for q in quiet:
            q.setLevel(logging.CRITICAL)
        try:
            if cluster is not None:
                client.run(_quiet_distributed_logs)  # the workers log their own heartbeat errors
            if futures:
                client.cancel(futures)  # after Ctrl-C: no chunk starts any more
            client.run(_runner.release, digest)  # the workers' extraction folders
        except Exception:
            pass
        client.close()
        if cluster is not None:
            cluster.close()
        for q, lv in zip(quiet, levels):
            q.setLevel(lv)


def regenerate(folder, workers=None, scheduler=None, progress=True):
    """Make the committed study in `folder` (a folder with sweep.json) anew from its spec (the
    path recorded in sweep.json), or every study in the subfolders of `folder`. Returns the
    list of (folder, DataFrame)."""
    folder = Path(folder)
    studies = (
        [folder] if (folder / META).exists() else sorted(p.parent for p in folder.glob(f"*/{META}"))
    )
    if not studies:
        raise SpecError(f"{folder}: no study (no {META} in it or in its subfolders)")
    done = []
    for study in studies:
        meta = json.loads((study / META).read_text())
        if "spec" not in meta:
            raise SpecError(f"{study}/{META} records no spec file: cannot regenerate")
        spec_path = (study / meta["spec"]).resolve()
        for name in PRODUCTS:
            (study / name).unlink(missing_ok=True)
        for svg in study.glob("*.svg"):
            svg.unlink()
        print(f"regenerating {study} from {spec_path}", file=sys.stderr)
        df = run_sweep(spec_path, study, workers=workers, scheduler=scheduler, progress=progress)
        done.append((study, df))
    return done
