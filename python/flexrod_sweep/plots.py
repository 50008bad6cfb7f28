"""Charts of a sweep (matplotlib, SVG): the resonance chart (a metric against crank speed, the
rod's omega_1 / k marked) and maps of a metric over two swept parameters (a cell map for a grid,
a triangulated contour map for scattered points such as a Latin hypercube).

What every chart shows: axis labels with the units of the model description; runs that failed
(status error, discard, diverged, timeout, exception) as marks on a strip at the foot of the
resonance chart (not as data values) with the lines broken at them, and as crosses on maps;
runs with the FMU's warning as open squares (resonance) or dots (maps); legends below the axes,
never on the data."""

import math
from collections import defaultdict

import numpy as np

OK = ("ok", "warning")
FAIL_MARKS = {
    "diverged": "x",
    "discard": "v",
    "error": "D",
    "timeout": "P",
    "exception": "*",
    "fatal": "D",
}


def _num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return float("nan")


def _lab(name, units):
    u = (units or {}).get(name, "")
    return f"{name} ({u})" if u else name


def _varying(spec, rows, exclude):
    names = [n for n in spec.swept_names() if n not in exclude]
    return [n for n in names if len({r[n] for r in rows}) > 1]


def _series(spec, rows, exclude):
    """Group rows by the values of the swept parameters not in `exclude` that vary."""
    varying = _varying(spec, rows, exclude)
    groups = defaultdict(list)
    for r in rows:
        groups[tuple((n, r[n]) for n in varying)].append(r)
    return groups


def _label(key):
    return ", ".join(f"{n} = {v}" for n, v in key) or "all runs"


def make_plots(spec, rows, out, units=None):
    import matplotlib

    matplotlib.use("Agg")
    written = []
    cfg = spec.plots
    rows = [r for r in rows if r.get("index", "") != ""]  # the current spec's runs only
    if "resonance" in cfg and rows:
        written += resonance_chart(spec, rows, out, cfg["resonance"], units)
    if "heatmap" in cfg and rows:
        written += heatmaps(spec, rows, out, cfg["heatmap"], units)
    return written


def omega_marks(rows, freq_name, harmonics):
    f = [_num(r.get(freq_name)) for r in rows]
    f = [x for x in f if math.isfinite(x)]
    if not f:
        return None, []
    w1 = 2 * math.pi * float(np.median(f))
    return w1, [(k, w1 / k) for k in harmonics]


def _continuous(rows, name, min_values=7):
    vals = {r[name] for r in rows}
    return len(vals) >= min_values and all(math.isfinite(_num(v)) for v in vals)


def _fail_strip(ax, xs, statuses, color):
    """Failed runs: marks on a strip at the foot of the axes (y in axes fraction), by status."""
    from matplotlib.transforms import blended_transform_factory

    tr = blended_transform_factory(ax.transData, ax.transAxes)
    # A grey band at the foot: the strip of runs without a value, outside the data's range.
    from matplotlib.patches import Rectangle

    ax.add_patch(Rectangle((0, 0), 1, 0.055, transform=ax.transAxes, color="0.92", zorder=0, lw=0))
    handles = []
    for st in sorted(set(statuses)):
        sel = [x for x, s in zip(xs, statuses) if s == st]
        h = ax.plot(
            sel,
            [0.025] * len(sel),
            FAIL_MARKS.get(st, "x"),
            color=color,
            ms=6,
            mfc="none",
            transform=tr,
            clip_on=False,
            label=f"{st} ({len(sel)})",
        )[0]
        handles.append(h)
    return handles


def resonance_chart(spec, rows, out, cfg, units=None):
    import matplotlib.pyplot as plt

    x = cfg.get("x", "crank.speed")
    metric = cfg.get("metric", spec.metrics[0])
    freq = cfg.get("frequency", "rod.frequency[1]")
    harmonics = cfg.get("harmonics", [2, 3, 4, 5, 6])
    normalized = cfg.get("normalized", False)
    others = _varying(spec, rows, {x})
    cont = [n for n in others if _continuous(rows, n)]
    if cont:  # a second continuous parameter: a map, not one series per value
        return heatmaps(
            spec,
            rows,
            out,
            {
                "x": x,
                "y": cont[0],
                "metric": metric,
                "file": cfg.get("file", "resonance.svg"),
                "title": cfg.get("title"),
                "frequency": freq,
                "harmonics": harmonics,
                "log": cfg.get("log", False),
            },
            units,
        )
    groups = _series(spec, rows, {x})
    n_panels = 2 if normalized else 1
    fig, axes = plt.subplots(
        n_panels,
        1,
        figsize=(9, 3.9 * n_panels + 1.2),
        sharex=True,
        squeeze=False,
        layout="constrained",
    )
    axes = axes[:, 0]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    xmin, xmax = math.inf, -math.inf
    w1s = []
    for i, (key, rs) in enumerate(sorted(groups.items())):
        c = colors[i % len(colors)]
        rs = sorted(rs, key=lambda r: _num(r[x]))
        xs = np.array([_num(r[x]) for r in rs])
        ys = np.array([_num(r[metric]) for r in rs])
        status = [r["status"] for r in rs]
        ok = np.array([s in OK for s in status])
        warn = np.array([s == "warning" for s in status])
        xmin, xmax = min(xmin, xs.min()), max(xmax, xs.max())
        name = _label(key)
        for p, (ax, yy) in enumerate(zip(axes, [ys, ys / xs**2])):
            yy = np.where(ok, yy, np.nan)  # the line breaks at failed runs
            ax.plot(xs, yy, "-o", ms=2.5, lw=1.2, color=c, label=name if p == 0 else None)
            if warn.any():
                ax.plot(
                    xs[warn],
                    yy[warn],
                    "s",
                    mfc="none",
                    ms=6,
                    color=c,
                    alpha=0.6,
                    label=f"{name}: FMU warning (large deflection)" if p == 0 else None,
                )
            if (~ok).any():
                hs = _fail_strip(ax, xs[~ok], [s for s, o in zip(status, ok) if not o], c)
                if p == 0:
                    for h in hs:
                        h.set_label(f"{name}: {h.get_label()}, marked at the foot")
                else:
                    for h in hs:
                        h.set_label(None)
        w1, _ = omega_marks(rs, freq, harmonics)
        if w1 is not None:
            w1s.append((w1, c, name))
    # omega_1 / k once per distinct omega_1 (the models of one rod share it).
    distinct = []
    for w1, c, name in w1s:
        if not any(abs(w1 - d[0]) < 1e-3 * w1 for d in distinct):
            distinct.append((w1, c, name))
    for j, (w1, c, name) in enumerate(distinct):
        col = "0.3" if len(distinct) == 1 else c
        for k in harmonics:
            w = w1 / k
            if not xmin <= w <= xmax:
                continue
            for ax in axes:
                ax.axvline(w, color=col, ls=":", lw=1)
            axes[0].annotate(
                f"$\\omega_1/{k}$",
                (w, 1.0),
                xycoords=("data", "axes fraction"),
                color=col,
                fontsize=8,
                ha="center",
                va="bottom",
                xytext=(0, 2 + 10 * j),
                textcoords="offset points",
            )
    axes[0].set_ylabel(_lab(metric, units))
    if normalized:
        u = (units or {}).get(metric, "")
        ux = (units or {}).get(x, "")
        axes[1].set_ylabel(f"{metric} / {x}$^2$" + (f" ({u}/({ux})$^2$)" if u and ux else ""))
    axes[-1].set_xlabel(_lab(x, units))
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.set_xlim(xmin, xmax)
        lo, hi = ax.get_ylim()  # room at the foot for the failed runs' strip, clear of data
        ax.set_ylim(lo - 0.07 * (hi - lo), hi)
    fig.legend(loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    title = cfg.get("title", f"{spec.name}: {metric} against {x}")
    if distinct:
        title += (
            "\n"
            + ", ".join(f"$\\omega_1$ = {w:.1f} rad/s" for w, _, _ in distinct)
            + " (dotted: $\\omega_1/k$)"
        )
    fig.suptitle(title, fontsize=10)
    path = out / cfg.get("file", "resonance.svg")
    fig.savefig(path)
    plt.close(fig)
    return [path]


def heatmaps(spec, rows, out, cfg, units=None):
    import matplotlib.patheffects as pe
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm
    from matplotlib.lines import Line2D

    x, y = cfg["x"], cfg["y"]
    metric = cfg.get("metric", spec.metrics[0])
    log = cfg.get("log", False)
    written = []
    stroke = [pe.withStroke(linewidth=3, foreground="k")]
    for i, (key, rs) in enumerate(sorted(_series(spec, rows, {x, y}).items())):
        xv = np.array([_num(r[x]) for r in rs])
        yraw = [r[y] for r in rs]
        cat_names = None
        if not all(math.isfinite(_num(v)) for v in yraw):  # enumeration items by name
            cat_names = list(dict.fromkeys(yraw))
            yv = np.array([cat_names.index(v) for v in yraw], dtype=float)
        else:
            yv = np.array([_num(v) for v in yraw])
        zv = np.array([_num(r[metric]) if r["status"] in OK else np.nan for r in rs])
        status = [r["status"] for r in rs]
        xs, ys = sorted(set(xv)), sorted(set(yv))
        gridded = len(xs) * len(ys) == len(rs)
        fig, ax = plt.subplots(figsize=(8, 5.6), layout="constrained")
        finite = zv[np.isfinite(zv)]
        pos = finite[finite > 0]
        vmin, vmax = cfg.get("vmin"), cfg.get("vmax")
        if log and len(pos):
            norm = LogNorm(vmin=vmin or max(pos.min(), 1e-12), vmax=vmax or pos.max(), clip=False)
        else:
            from matplotlib.colors import Normalize

            norm = Normalize(vmin=vmin, vmax=vmax) if vmin is not None or vmax is not None else None
        extend = (
            "both"
            if vmin is not None and vmax is not None
            else "min"
            if vmin is not None
            else "max"
            if vmax is not None
            else "neither"
        )
        contours = cfg.get("contour")
        contours = (
            []
            if contours is None
            else sorted(contours if isinstance(contours, list) else [contours])
        )
        cmap = cfg.get("cmap", "viridis")
        handles = []
        if gridded:
            # Unevenly spaced (or categorical) y values: equal rows, labelled with the values.
            # (A few uneven values, e.g. damping ratios 0, 0.25, 0.5, 1 %; many values keep their
            # true positions.)
            cat_y = cat_names is not None or (
                2 < len(ys) <= 8 and np.ptp(np.diff(ys)) > 1e-9 * max(abs(ys[-1]), 1)
            )
            ypos = {v: (j if cat_y else v) for j, v in enumerate(ys)}
            z = np.full((len(ys), len(xs)), np.nan)
            for a, b, c in zip(xv, yv, zv):
                z[ys.index(b), xs.index(a)] = c
            py = np.array([ypos[v] for v in yv])
            ycoords = [ypos[v] for v in ys]
            mesh = ax.pcolormesh(
                _edges(xs), _edges(ycoords), z, shading="flat", cmap=cmap, norm=norm
            )
            if contours and np.isfinite(z).sum() > 3:
                cs = ax.contour(
                    xs, ycoords, z, levels=contours, colors="w", linewidths=1.5, path_effects=stroke
                )
                if len(contours) > 1:
                    ax.clabel(cs, fmt="%g", fontsize=8, colors="k")
            if cat_y:
                ax.set_yticks(ycoords)
                ax.set_yticklabels(cat_names if cat_names else [f"{v:g}" for v in ys])
        else:
            # Scattered points (a Latin hypercube): a contour map over their triangulation.
            py = yv
            good = np.isfinite(zv)
            if good.sum() >= 3:
                import matplotlib.tri as mtri

                tri = mtri.Triangulation(xv[good], yv[good])
                levels = np.geomspace(pos.min(), pos.max(), 12) if norm is not None else 12
                mesh = ax.tricontourf(tri, zv[good], levels=levels, cmap=cmap, norm=norm)
                if contours:
                    ax.tricontour(
                        tri,
                        zv[good],
                        levels=contours,
                        colors="w",
                        linewidths=1.5,
                        path_effects=stroke,
                    )
            else:
                mesh = ax.scatter(xv, yv, c=zv, cmap=cmap, norm=norm)
            ax.plot(xv[good], yv[good], ".", color="k", ms=2)
            handles.append(
                Line2D(
                    [],
                    [],
                    ls="none",
                    marker=".",
                    color="k",
                    ms=4,
                    label=f"run ({good.sum()} finished)",
                )
            )
        fig.colorbar(mesh, ax=ax, label=_lab(metric, units), extend=extend)
        if contours:
            handles.append(
                Line2D(
                    [],
                    [],
                    color="w",
                    lw=1.5,
                    path_effects=stroke,
                    label=f"contour: {metric} = {', '.join(f'{c:g}' for c in contours)}",
                )
            )
        warn = [(a, b) for a, b, s in zip(xv, py, status) if s == "warning"]
        if warn:
            ax.plot(*zip(*warn), ".", color="orange", ms=3)
            handles.append(
                Line2D(
                    [],
                    [],
                    ls="none",
                    marker=".",
                    color="orange",
                    label=f"FMU warning: large deflection ({len(warn)})",
                )
            )
        for st in sorted({s for s in status if s not in OK}):
            pts = [(a, b) for a, b, s in zip(xv, py, status) if s == st]
            ax.plot(*zip(*pts), FAIL_MARKS.get(st, "x"), color="red", ms=6, mfc="none")
            handles.append(
                Line2D(
                    [],
                    [],
                    ls="none",
                    marker=FAIL_MARKS.get(st, "x"),
                    color="red",
                    mfc="none",
                    label=f"{st} ({len(pts)}): no value",
                )
            )
        if "frequency" in cfg and x == "crank.speed":
            _, marks = omega_marks(rs, cfg["frequency"], cfg.get("harmonics", [2, 3, 4]))
            for k, w in marks:
                if xs[0] <= w <= xs[-1]:
                    ax.axvline(w, color="w", ls=":", lw=1)
                    ax.annotate(
                        f"$\\omega_1/{k}$",
                        (w, 0.98),
                        xycoords=("data", "axes fraction"),
                        ha="center",
                        va="top",
                        fontsize=8,
                        color="w",
                        path_effects=stroke,
                    )
            if marks:
                handles.append(
                    Line2D(
                        [],
                        [],
                        color="0.5",
                        ls=":",
                        lw=1,
                        label="$\\omega_1/k$: crank speeds where the k-th harmonic meets the first bending mode",
                    )
                )
        ax.set_xlabel(_lab(x, units))
        ax.set_ylabel(_lab(y, units))
        if handles:
            fig.legend(
                handles=handles, loc="outside lower center", ncol=2, fontsize=8, frameon=False
            )
        title = cfg.get("title") or f"{spec.name}: {metric}"
        ax.set_title(title + (f"\n{_label(key)}" if key else ""), fontsize=10)
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
        return (
            np.array([v[0] - 0.5, v[0] + 0.5])
            if v[0] == 0
            else np.array([v[0] * 0.95, v[0] * 1.05])
        )
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
