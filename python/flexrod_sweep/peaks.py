"""Resonance peaks of a finished sweep against omega_1 / k and the axial-load shift.

    python -m flexrod_sweep.peaks DIR [--metric M] [--harmonics 2 3 4 5 6]

For each series (e.g. rod.model) and k: the local maximum of metric / Omega^2 (the dynamic
amplification: the quasi-static deflection grows as Omega^2) within +-8 % of omega_1 / k,
refined by a parabola through the three points around it. The shift explained by the axial
load: a pinned-pinned rod under a uniform axial force N has omega^2 = omega_1^2 (1 + N / P_cr),
P_cr = pi^2 E I / L^2; with the cycle mean of the rod's axial force (metric
mean(rod.axial_force), which grows as Omega^2: N = c Omega^2) the k-th peak sits where
k Omega = omega_1 sqrt(1 + c Omega^2 / P_cr), i.e. Omega_k = omega_1 / sqrt(k^2 - omega_1^2 c / P_cr).
"""

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

AXIAL = "mean(rod.axial_force)"


def p_cr(fmu_spec_dir):
    from fmpy import read_model_description

    from .spec import load

    spec = load(Path(fmu_spec_dir) / "spec.toml")
    md = read_model_description(str(Path(fmu_spec_dir) / "modelDescription.xml"))
    start = {
        v.name: float(v.start)
        for v in md.modelVariables
        if v.type == "Real" and v.start is not None
    }
    ei = start["rod.youngs_modulus"] * start["rod.area_moment"]
    return math.pi**2 * ei / start["rod.length"] ** 2, spec


def analyse(out, metric="max_abs(rod.deflection_rel)", harmonics=(2, 3, 4, 5, 6), window=0.08):
    out = Path(out)
    pcr, spec = p_cr(out)
    rows = list(csv.DictReader(open(out / "results.csv", newline="")))
    others = [n for n in spec.swept_names() if n != "crank.speed" and len({r[n] for r in rows}) > 1]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[n] for n in others), []).append(r)
    table = []
    for key, rs in sorted(groups.items()):
        rs = [r for r in rs if r["status"] in ("ok", "warning")]
        rs.sort(key=lambda r: float(r["crank.speed"]))
        w = np.array([float(r["crank.speed"]) for r in rs])
        y = np.array([float(r[metric]) for r in rs]) / w**2
        w1 = 2 * math.pi * float(np.median([float(r["rod.frequency[1]"]) for r in rs]))
        c = np.array([float(r[AXIAL]) for r in rs]) / w**2 if AXIAL in rs[0] else None
        for k in harmonics:
            target = w1 / k
            idx = np.where(np.abs(w - target) <= window * target)[0]
            idx = [i for i in idx if 0 < i < len(w) - 1 and y[i] >= y[i - 1] and y[i] >= y[i + 1]]
            if not idx:
                table.append((key, k, target, None, None, None, None))
                continue
            i = max(idx, key=lambda j: y[j])
            # parabola through (w[i-1], w[i], w[i+1])
            a, b, _ = np.polyfit(w[i - 1 : i + 2], y[i - 1 : i + 2], 2)
            peak = -b / (2 * a) if a < 0 else w[i]
            shifted = None
            if c is not None:
                cc = float(np.interp(peak, w, c))
                shifted = w1 / math.sqrt(k * k - w1 * w1 * cc / pcr)
            table.append(
                (
                    key,
                    k,
                    target,
                    peak,
                    shifted,
                    float(np.interp(peak, w, y * w**2)),
                    cc * peak**2 if c is not None else None,
                )
            )
    return others, w1, pcr, table


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m flexrod_sweep.peaks")
    p.add_argument("out")
    p.add_argument("--metric", default="max_abs(rod.deflection_rel)")
    p.add_argument("--harmonics", type=int, nargs="+", default=[2, 3, 4, 5, 6])
    a = p.parse_args(argv)
    others, w1, pcr, table = analyse(a.out, a.metric, a.harmonics)
    print(
        f"omega_1 = {w1:.2f} rad/s (median of rod.frequency[1]), P_cr = {pcr:.1f} N; peaks of {a.metric} / Omega^2"
    )
    print()
    print(
        f"| {', '.join(others) or 'series'} | k | omega_1/k (rad/s) | peak (rad/s) | peak - omega_1/k | "
        "mean axial force at peak (N) | predicted with axial load (rad/s) | peak - predicted | peak value |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for key, k, target, peak, shifted, val, n in table:
        name = ", ".join(key) or "all"
        if peak is None:
            print(f"| {name} | {k} | {target:.1f} | no local maximum within 8 % | | | | | |")
            continue
        if shifted is None:
            print(
                f"| {name} | {k} | {target:.1f} | {peak:.1f} | {100 * (peak / target - 1):+.2f} % | "
                f"(no {AXIAL} metric) | | | {val:.4g} |"
            )
            continue
        print(
            f"| {name} | {k} | {target:.1f} | {peak:.1f} | {100 * (peak / target - 1):+.2f} % | "
            f"{n:.1f} | {shifted:.1f} | {100 * (peak / shifted - 1):+.2f} % | {val:.4g} |"
        )


if __name__ == "__main__":
    sys.exit(main())
