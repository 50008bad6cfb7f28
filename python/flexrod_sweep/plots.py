"""Charts of a sweep (matplotlib, SVG): the resonance chart (a metric against crank speed, the
rod's omega_1 / k marked) and heat maps of a metric over two swept parameters."""

import math
from collections import defaultdict

import numpy as np


def _num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return float("nan")


def _series(spec, rows, exclude):
    """Group rows by the values of the swept parameters not in `exclude` that vary."""
    names = [n for n in spec.swept_names() if n not in exclude]
    varying = [n for n in names if len({r[n] for r in rows}) > 1]
    groups = defaultdict(list)
    for r in rows:
        groups[tuple((n, r[n]) for n in varying)].append(r)
    return groups


def _label(key):
    return ", ".join(f"{n} = {v}" for n, v in key) or "all runs"


def make_plots(spec, rows, out):
    import matplotlib

    matplotlib.use("Agg")
    written = []
    cfg = spec.plots
    if "resonance" in cfg and rows:
        written += resonance_chart(spec, rows, out, cfg["resonance"])
    if "heatmap" in cfg and rows:
        written += heatmaps(spec, rows, out, cfg["heatmap"])
    return written


def omega_marks(rows, freq_name, harmonics):
    f = [_num(r.get(freq_name)) for r in rows]
    f = [x for x in f if math.isfinite(x)]
    if not f:
        return None, []
    w1 = 2 * math.pi * float(np.median(f))
    return w1, [(k, w1 / k) for k in harmonics]


def resonance_chart(spec, rows, out, cfg):
    import matplotlib.pyplot as plt

    x = cfg.get("x", "crank.speed")
    metric = cfg.get("metric", spec.metrics[0])
    freq = cfg.get("frequency", "rod.frequency[1]")
    harmonics = cfg.get("harmonics", [2, 3, 4, 5, 6])
    normalized = cfg.get("normalized", False)
    groups = _series(spec, rows, {x})
    n_panels = 2 if normalized else 1
    fig, axes = plt.subplots(n_panels, 1, figsize=(9, 4.2 * n_panels), sharex=True, squeeze=False)
    axes = axes[:, 0]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    xmin, xmax = math.inf, -math.inf
    for i, (key, rs) in enumerate(sorted(groups.items())):
        c = colors[i % len(colors)]
        rs = sorted(rs, key=lambda r: _num(r[x]))
        xs = np.array([_num(r[x]) for r in rs])
        ys = np.array([_num(r[metric]) for r in rs])
        ok = np.array([r["status"] in ("ok", "warning") for r in rs])
        warn = np.array([r["status"] == "warning" for r in rs])
        xmin, xmax = min(xmin, xs.min()), max(xmax, xs.max())
        for ax, yy in zip(axes, [ys, ys / xs**2]):
            ax.plot(xs[ok], yy[ok], "-o", ms=3, color=c, label=_label(key))
            if warn.any():
                ax.plot(xs[warn], yy[warn], "s", mfc="none", ms=7, color=c,
                        label=f"{_label(key)}: large-deflection warning")
            if (~ok).any():
                ax.plot(xs[~ok], np.full((~ok).sum(), np.nanmin(yy[ok]) if ok.any() else 0), "x",
                        color=c, ms=8, label=f"{_label(key)}: failed")
        w1, marks = omega_marks(rs, freq, harmonics)
        for k, w in marks:
            for ax in axes:
                ax.axvline(w, color=c, ls=":", lw=1)
            axes[0].annotate(f"$\\omega_1/{k}$", (w, 1.0), xycoords=("data", "axes fraction"),
                             color=c, fontsize=8, ha="center", va="bottom",
                             xytext=(0, 2 + 10 * i), textcoords="offset points")
    axes[0].set_ylabel(metric)
    if normalized:
        axes[1].set_ylabel(f"{metric} / {x}$^2$")
    axes[-1].set_xlabel(x + " (rad/s)" if x == "crank.speed" else x)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.set_xlim(xmin, xmax)
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(cfg.get("title", f"{spec.name}: {metric} against {x}"), y=0.995)
    fig.tight_layout()
    path = out / cfg.get("file", "resonance.svg")
    fig.savefig(path)
    plt.close(fig)
    return [path]


def heatmaps(spec, rows, out, cfg):
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    x, y = cfg["x"], cfg["y"]
    metric = cfg.get("metric", spec.metrics[0])
    log = cfg.get("log", False)
    written = []
    for i, (key, rs) in enumerate(sorted(_series(spec, rows, {x, y}).items())):
        xs = sorted({_num(r[x]) for r in rs})
        ys = sorted({_num(r[y]) for r in rs})
        z = np.full((len(ys), len(xs)), np.nan)
        bad = []
        warn = []
        for r in rs:
            ix, iy = xs.index(_num(r[x])), ys.index(_num(r[y]))
            if r["status"] in ("ok", "warning"):
                z[iy, ix] = _num(r[metric])
                if r["status"] == "warning":
                    warn.append((xs[ix], ys[iy]))
            else:
                bad.append((xs[ix], ys[iy]))
        # Unevenly spaced (or categorical) y values: equal rows, labelled with the values.
        cat_y = len(ys) > 2 and np.ptp(np.diff(ys)) > 1e-9 * max(abs(ys[-1]), 1)
        ypos = list(range(len(ys))) if cat_y else ys
        warn = [(wx, ypos[ys.index(wy)]) for wx, wy in warn]
        bad = [(bx, ypos[ys.index(by)]) for bx, by in bad]
        fig, ax = plt.subplots(figsize=(8, 5))
        finite = z[np.isfinite(z)]
        norm = LogNorm(vmin=max(finite[finite > 0].min(), 1e-12), vmax=finite.max()) if log and (finite > 0).any() else None
        mesh = ax.pcolormesh(_edges(xs), _edges(ypos), z, shading="flat", cmap=cfg.get("cmap", "viridis"), norm=norm)
        fig.colorbar(mesh, ax=ax, label=metric)
        if cfg.get("contour") is not None and np.isfinite(z).sum() > 3:
            ax.contour(xs, ypos, z, levels=[cfg["contour"]], colors="w", linewidths=1.5)
        if warn:
            ax.plot(*zip(*warn), ".", color="orange", ms=3, label="large-deflection warning (|v/L| > 0.05)")
        if bad:
            ax.plot(*zip(*bad), "x", color="red", ms=7, label="failed (discard / error / diverged)")
        if "frequency" in cfg and x == "crank.speed":
            _, marks = omega_marks(rs, cfg["frequency"], cfg.get("harmonics", [2, 3, 4]))
            for k, w in marks:
                if xs[0] <= w <= xs[-1]:
                    ax.axvline(w, color="w", ls=":", lw=1)
                    ax.annotate(f"$\\omega_1/{k}$", (w, 1.0), xycoords=("data", "axes fraction"),
                                ha="center", va="bottom", fontsize=8)
        ax.set_xlabel(x + (" (rad/s)" if x == "crank.speed" else ""))
        ax.set_ylabel(y)
        if cat_y:
            ax.set_yticks(ypos)
            ax.set_yticklabels([f"{v:g}" for v in ys])
        if warn or bad:
            ax.legend(fontsize=8, loc="upper left")
        ax.set_title(cfg.get("title", f"{spec.name}: {metric}") + (f"\n{_label(key)}" if key else ""), fontsize=10)
        fig.tight_layout()
        stem = cfg.get("file", "heatmap.svg").rsplit(".", 1)
        suffix = "" if not key else "_" + "_".join(str(v) for _, v in key)
        path = out / f"{stem[0]}{suffix}.{stem[1] if len(stem) > 1 else 'svg'}"
        fig.savefig(path)
        plt.close(fig)
        written.append(path)
    return written


def _edges(v):
    v = np.asarray(v, dtype=float)
    if len(v) == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5]) if v[0] == 0 else np.array([v[0] * 0.95, v[0] * 1.05])
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
