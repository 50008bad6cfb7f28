"""Draw docs/figures/automotive_stress.svg: the stress at mid-length of the automotive rod
(scenes/automotive_rod.toml, FFR as shipped) against the crank angle, with the independent
geometrically exact shear beam (Exudyn, tests/data/exudyn_automotive_rod.csv), over the ramp to
6000 rpm and two revolutions with the 38 kN gas pulse. The data come from
`FLEXROD_BLESS=1 cargo test --release --test automotive_reference`, which writes
docs/figures/automotive_stress.csv.

    .venv/bin/python docs/figures/automotive_stress.py   (from the repository root)
"""

import csv

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "flexrod"  # reproducible element ids
import matplotlib.pyplot as plt  # noqa: E402

with open("docs/figures/automotive_stress.csv") as f:
    rows = [r for r in csv.DictReader(f)]
t = [float(r["t_s"]) for r in rows]
angle = [float(r["crank_angle_deg"]) for r in rows]
ffr = [float(r["ffr_stress_mpa"]) for r in rows]
ref = [float(r["reference_stress_mpa"]) for r in rows]
# The two revolutions at full speed (after the 40 ms ramp).
keep = [k for k, x in enumerate(t) if x >= 0.04]
a0 = angle[keep[0]]
x = [angle[k] - a0 for k in keep]

fig, ax = plt.subplots(figsize=(8, 3.6))
ax.plot(x, [ref[k] for k in keep], color="black", lw=2.2, label="geometrically exact shear beam (Exudyn, 64 elements)")
ax.plot(x, [ffr[k] for k in keep], color="#ff7f0e", lw=1.0, label="flexrod FFR, scene as shipped (8 elements, 7 modes)")
ax.set_xlabel("crank angle after the ramp, degrees")
ax.set_ylabel("stress at L/2, MPa\n|N|/A + |M| c/I")
ax.set_title("Automotive rod at 6000 rpm with a 38 kN gas pulse")
ax.set_xticks(range(0, 721, 90))
ax.grid(alpha=0.3)
ax.set_ylim(0, 160)
ax.legend(loc="upper right", fontsize=8)
fig.tight_layout()
fig.savefig("docs/figures/automotive_stress.svg", metadata={"Date": None})
print("wrote docs/figures/automotive_stress.svg")
