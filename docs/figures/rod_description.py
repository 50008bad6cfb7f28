"""Draw docs/figures/rod_description.svg: how a scene describes a real rod, from the scene itself
(default scenes/automotive_rod.toml). Stations of [[rod.section]] along B -> C with their area,
area moment and fibre distance (the outline is +-fibre_distance, linear between stations), the
end bodies [rod.big_end] at B and [rod.small_end] at C, the crank and the slider line
y = [mechanism] slider_offset.

    .venv/bin/python docs/figures/rod_description.py [SCENE] [--out FILE]   (from the repository root)
"""

import argparse
import tomllib

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "flexrod"  # reproducible element ids
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("scene", nargs="?", default="scenes/automotive_rod.toml")
ap.add_argument("--out", default="docs/figures/rod_description.svg")
args = ap.parse_args()
with open(args.scene, "rb") as f:
    scene = tomllib.load(f)
rod = scene["rod"]
L = rod["length"]
r = scene["crank"]["length"]
e = scene.get("mechanism", {}).get("slider_offset", 0.0)
stations = rod["section"]
mm = 1e3

fig, ax = plt.subplots(figsize=(11, 5.2))
# Rod axis from B at x = 0 to C at x = L (drawn horizontal; in the mechanism B is on the crank).
xs = [st["position"] * mm for st in stations]
cs = [st.get("fibre_distance", 0.0) * mm for st in stations]
ax.fill_between(xs, [-c for c in cs], cs, color="#cfd8e3", zorder=1, label="outline: +- fibre_distance")
ax.plot([0, L * mm], [0, 0], "k-.", lw=0.8, zorder=2)
for k, st in enumerate(stations):
    x, c = st["position"] * mm, st.get("fibre_distance", 0.0) * mm
    ax.plot([x, x], [-c, c], color="#1f4e79", lw=1.5, zorder=3)
    ax.annotate(
        f"station {k}\nposition = {st['position']:g} m\narea = {st['area']:.3g} m2\n"
        f"area_moment = {st['area_moment']:.4g} m4\nfibre_distance = {st.get('fibre_distance', float('nan')):g} m",
        xy=(x, c),
        xytext=(x, 34 + (k % 2) * 0),
        ha="center",
        va="bottom",
        fontsize=8,
        arrowprops=dict(arrowstyle="-", color="#1f4e79", lw=0.6),
    )
    ax.add_patch(
        FancyArrowPatch((x + 1.2, 0), (x + 1.2, c), arrowstyle="<->", mutation_scale=7, color="#c00000", lw=0.8)
    )
ax.text(xs[0] + 2.0, cs[0] * 0.45, "c", color="#c00000", fontsize=9)
# End bodies.
for x, key, label in ((0.0, "big_end", "B"), (L * mm, "small_end", "C")):
    body = rod.get(key, {})
    rad = 9 if key == "big_end" else 6
    ax.add_patch(Circle((x, 0), rad, fill=False, ec="#7f6000", lw=2, zorder=4))
    ax.plot([x], [0], "ko", ms=4, zorder=5)
    ax.text(
        x,
        -rad - 4,
        f"{label}: [rod.{key}]\nmass = {body.get('mass', 0):g} kg\ninertia = {body.get('inertia', 0):g} kg m2 about {label}",
        ha="center",
        va="top",
        fontsize=8,
        color="#7f6000",
    )
# Crank circle around A (drawn to the left of B) and the slider block at C.
ax_a = -r * mm
ax.add_patch(Circle((ax_a, 0), r * mm, fill=False, ls="--", ec="gray", lw=0.8))
ax.plot([ax_a, 0], [0, 0], color="gray", lw=2)
ax.plot([ax_a], [0], "ks", ms=5)
ax.text(ax_a, 4, "A (crank axis)\ncrank.length = %g m" % r, ha="center", va="bottom", fontsize=8, color="gray")
ax.add_patch(Rectangle((L * mm - 8, e * mm - 7), 16, 14, fill=False, ec="gray", lw=1.2, zorder=2))
ax.plot([L * mm - 30, L * mm + 40], [e * mm, e * mm], color="gray", lw=0.8, ls=":")
ax.text(
    L * mm + 12,
    e * mm + 9,
    "slider on y = slider_offset\n([mechanism], here %g m)" % e,
    fontsize=8,
    color="gray",
    va="bottom",
)
ax.annotate("", xy=(L * mm, -52), xytext=(0, -52), arrowprops=dict(arrowstyle="<->", lw=0.8))
ax.text(L * mm / 2, -55, "rod.length = %g m (B to C); properties linear between stations" % L, ha="center", va="top", fontsize=8)
ax.set_aspect("equal")
ax.set_xlim(ax_a - r * mm - 5, L * mm + 60)
ax.set_ylim(-72, 78)
ax.axis("off")
ax.set_title(f"Describing a rod: {scene.get('name', '')} ({args.scene}), dimensions in mm", fontsize=10)
ax.legend(loc="lower right", fontsize=8, frameon=False)
fig.tight_layout()
fig.savefig(args.out, metadata={"Date": None})
print("wrote", args.out)
