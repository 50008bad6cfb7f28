"""Orchestration: FMU (given or exported from a scene), validation, the runs in chunks on Dask
(a LocalCluster, a scheduler address, or in this process), results.csv (resumable), plots."""

import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from . import runner as _runner
from .spec import SpecError, load

META = "sweep.json"


def find_root(start):
    for p in [Path(start).resolve(), *Path(start).resolve().parents]:
        if (p / "Cargo.toml").exists() and (p / "fmu").is_dir():
            return p
    raise SpecError(f"[fmu] scene: no flexrod workspace (Cargo.toml with fmu/) above {start}")


def export_scene(spec, out):
    """`cargo run --release -p fmu -- SCENE --out OUT/fmu` (with the spec's scene overrides
    written into a copy of the scene); returns the .fmu path."""
    scene = spec.scene
    if not scene.exists():
        raise SpecError(f"[fmu] scene {scene} does not exist")
    fmu_dir = out / "fmu"
    fmu_dir.mkdir(parents=True, exist_ok=True)
    if spec.scene_overrides:
        text = scene.read_text()
        for key, value in spec.scene_overrides.items():
            table, k = key.rsplit(".", 1)
            val = json.dumps(value) if isinstance(value, str) else repr(value).lower() if isinstance(value, bool) else repr(value)
            pat = re.compile(rf"(\[{re.escape(table)}\][^\[]*?^{re.escape(k)}\s*=\s*)[^\n#]*", re.M | re.S)
            text, n = pat.subn(lambda m: m.group(1) + val, text, count=1)
            if n == 0:
                raise SpecError(f"[fmu] scene_overrides: no key {k!r} in table [{table}] of {scene}")
        scene = fmu_dir / "scene.toml"
        scene.write_text(text)
    root = find_root(spec.scene.parent)
    cmd = ["cargo", "run", "--release", "-q", "-p", "fmu", "--", str(scene), "--out", str(fmu_dir)]
    res = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
    if res.returncode != 0:
        raise SpecError(f"exporting {scene} failed:\n{res.stdout}\n{res.stderr}")
    for line in res.stdout.splitlines():
        if line.startswith("wrote ") and ".fmu" in line:
            return Path(line.split(" ")[1])
    raise SpecError(f"the packager reported no .fmu:\n{res.stdout}")


def columns(spec):
    return (["run", *spec.swept_names(), *spec.metrics, *spec.record, "status", "message", "wall_time"])


def fmt(x):
    if isinstance(x, float):
        return repr(x)
    return str(x)


def read_results(path):
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def key_of(shown):
    return json.dumps({k: shown[k] for k in sorted(shown)}, sort_keys=True)


def row_key(row, names):
    vals = {}
    for n in names:
        s = row[n]
        try:
            v = float(s)
            if v == int(v) and re.fullmatch(r"-?\d+", s):
                v = int(s)
        except ValueError:
            v = {"True": True, "False": False}.get(s, s)
        vals[n] = v
    return json.dumps({k: vals[k] for k in sorted(vals)}, sort_keys=True)


def normalise(shown):
    """Values as they read back from the CSV (ints stay ints, floats as floats)."""
    return {k: (float(v) if isinstance(v, float) else v) for k, v in shown.items()}


def make_chunks(todo, n_chunks):
    n_chunks = max(1, min(n_chunks, len(todo)))
    # Interleaved so that every chunk gets a mix of cheap and dear runs.
    return [todo[i::n_chunks] for i in range(n_chunks)]


def run_sweep(spec_path, out, scheduler=None, workers=None, chunks_per_worker=4, progress=True,
              plots=True, retry_failed=False):
    """Run (or resume) a sweep; returns the list of result rows (dicts, CSV strings)."""
    from fmpy import read_model_description

    spec = load(spec_path)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    fmu_path = spec.fmu_path if spec.fmu_path is not None else export_scene(spec, out)
    if not Path(fmu_path).exists():
        raise SpecError(f"[fmu] path {fmu_path} does not exist (build it: cargo run --release -p fmu)")
    md = read_model_description(str(fmu_path))
    runs = spec.validate(md)  # every check before any run
    fmu_bytes = Path(fmu_path).read_bytes()
    digest = _runner.fmu_digest(fmu_bytes)

    meta_path = out / META
    meta = {"definition": spec.definition_hash(), "fmu": digest, "columns": columns(spec)}
    results_path = out / "results.csv"
    if meta_path.exists() and results_path.exists():
        old = json.loads(meta_path.read_text())
        if old != meta:
            raise SpecError(f"{out} holds results of another FMU, drive, metric set or columns "
                            f"({old} vs {meta}); choose another --out or delete it")
    meta_path.write_text(json.dumps(meta, indent=1))
    shutil.copyfile(spec_path, out / "spec.toml")
    import zipfile

    with zipfile.ZipFile(fmu_path) as z:  # the FMU's description, for the record and the analysis
        (out / "modelDescription.xml").write_bytes(z.read("modelDescription.xml"))

    names = spec.swept_names()
    existing = read_results(results_path)
    done = {}
    for row in existing:
        if retry_failed and row["status"] not in ("ok", "warning"):
            continue
        done[row_key(row, names)] = row
    todo = []
    for run_id, (fmu_values, shown) in enumerate(runs):
        if key_of(normalise(shown)) not in done:
            todo.append((run_id, fmu_values, {k: fmt(v) for k, v in shown.items()}))
    # Keep only finished rows in the file (drop retried failures), then append.
    cols = columns(spec)
    keep = [r for r in existing if row_key(r, names) in done]
    with open(results_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in keep:
            w.writerow({c: r.get(c, "") for c in cols})

    args = (spec.drive, spec.metrics, spec.record, _outputs(spec), spec.abort)
    info = {"runs": len(runs), "skipped": len(runs) - len(todo), "ran": len(todo)}
    t0 = time.perf_counter()
    if todo:
        if workers == 0 and scheduler is None:
            _serial(fmu_bytes, todo, args, results_path, cols, progress)
        else:
            _dask(fmu_bytes, todo, args, results_path, cols, progress, scheduler, workers,
                  chunks_per_worker, info)
    info["elapsed"] = time.perf_counter() - t0
    rows = read_results(results_path)
    rows.sort(key=lambda r: int(r["run"]))
    with open(results_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)
    if plots:
        from .plots import make_plots

        info["plots"] = [str(p) for p in make_plots(spec, rows, out)]
    (out / "last_run.json").write_text(json.dumps(info, indent=1))
    return rows, info


def _outputs(spec):
    from .runner import DERIVED, parse_metric

    outs = []
    for m in spec.metrics:
        o = parse_metric(m)[1]
        for x in DERIVED.get(o, [o]):
            if x not in outs:
                outs.append(x)
    for o in spec.abort:
        if o not in outs:
            outs.append(o)
    return outs


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


def _serial(fmu_bytes, todo, args, results_path, cols, progress):
    with _bar(len(todo), progress) as bar:
        for item in todo:
            rows = _runner.run_chunk(fmu_bytes, [item], *args)
            _append(results_path, cols, rows)
            bar.update(1)


def _dask(fmu_bytes, todo, args, results_path, cols, progress, scheduler, workers, cpw, info):
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    t_up = time.perf_counter()
    if scheduler is None:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=None, host="127.0.0.1")
        client = Client(cluster)
    else:
        client = Client(scheduler)
    try:
        n_workers = max(1, len(client.scheduler_info()["workers"]))
        info["workers"] = n_workers
        # The FMU goes to every worker once (works across machines: no shared file system).
        fmu_future = client.scatter(fmu_bytes, broadcast=True)
        info["startup"] = time.perf_counter() - t_up
        # Small chunks (about 10 runs) keep the progress bar moving; the FMU still loads once
        # per worker (the instance is cached in the worker process).
        chunks = make_chunks(todo, max(n_workers * cpw, math.ceil(len(todo) / 10)))
        futures = [client.submit(_runner.run_chunk, fmu_future, chunk, *args, pure=False)
                   for chunk in chunks]
        with _bar(len(todo), progress) as bar:
            for fut in as_completed(futures):
                try:
                    rows = fut.result()
                except Exception as e:  # a lost worker or chunk: its runs become rows too
                    idx = futures.index(fut)
                    rows = [{"run": rid, **shown, "status": "exception",
                             "message": f"chunk failed: {type(e).__name__}: {e}", "wall_time": float("nan")}
                            for rid, _, shown in chunks[idx]]
                _append(results_path, cols, rows)
                bar.update(len(rows))
    finally:
        import logging

        # Closing a LocalCluster can log heartbeat errors of workers already gone: noise.
        quiet = [logging.getLogger(n) for n in ("distributed", "distributed.worker", "distributed.nanny")]
        levels = [q.level for q in quiet]
        for q in quiet:
            q.setLevel(logging.CRITICAL)
        client.close()
        if cluster is not None:
            cluster.close()
        for q, lv in zip(quiet, levels):
            q.setLevel(lv)
