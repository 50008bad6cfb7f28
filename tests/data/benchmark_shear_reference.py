"""Shear-deformable reference for the benchmark rod (scenes/benchmark.toml): Exudyn's
geometrically exact 2D beam (ObjectBeamGeometricallyExact2D, Simo-Reissner, linear elements) in
the slider-crank at a constant crank speed W (--speed, 150 rad/s by default: the run of
tests/data/exudyn_ancf_150rad_s.csv, Exudyn ANCF cable, no shear deformation, with shear
deformation and the section's rotary inertia).

The run:
- the rod of the scene: length L, E (times --youngs-scale, 1 by default), rho, area A, area
  moment I, crank radius r, slider mass; shear modulus G = E / 2.6 (nu = 0.3), shear area
  A / 1.2, cross-section inertia rho I; no damping, no gravity.
- crank angle theta = W t exactly from t = 0 (abrupt start). At t = 0 the rod is undeformed
  along x from pin B (r, 0) to pin C (r + L, 0) and moves rigidly with the crank: the node at arc
  length s has the velocity (0, r W (1 - s/L)) and the rotation rate -r W / L; the slider is at
  rest.
- the beam: N elements of equal length (NodeRigidBody2D nodes). Pin B: the first node's x and y
  prescribed by coordinate constraints (user functions of theta). Pin C: with the scene's slider
  mass 0, the last node's y is held at 0 by a coordinate constraint (no slider body: Exudyn's
  mass point needs a mass); with a slider mass m > 0, a MassPoint2D of mass m on y = 0, pinned
  to the last node by a revolute joint. Generalized-alpha (spectral radius --rho-inf), fixed
  step h, full Newton (relative tolerance 1e-8, absolute --newton-abs: the residual's round-off
  floor grows with the number of elements, 512 elements need 1e-4; at 64 elements 1e-5 and 1e-6
  give the same v_mid to 1e-10 of its peak), sparse linear solver.

Elements: the linear elements converge as 1/N^2 in v_mid (largest difference over the peak:
32 -> 64 elements 1.4e-2, 64 -> 128 3.7e-3, 128 -> 256 9.5e-4, 256 -> 512 2.3e-4, h = 5e-7 s),
hence 512 elements for the stored run (its remaining error, from the extrapolation of 256 and
512 elements, 8e-5 of the peak; h = 1e-6 s against 5e-7 s: 1e-4). The pin forces do not
converge pointwise at that level: the abrupt start rings the rod's axial modes (the first near
4.2 kHz, undamped), whose phase at the 1e-4 s samples moves with N and h (256 -> 512 elements
6 % of the peak FBx, h 1e-6 -> 5e-7 s 10 %); compare v_mid, or the forces' envelope.

Same run as the ANCF file: --euler-bernoulli (shear stiffness x 1e3) with
--section-inertia-scale 1e-3 (no rotary inertia) gives the cable's physics, which must approach
the ANCF file as N grows: 256 elements 3.0e-4 of the peak v_mid off, the extrapolation of 128
and 256 elements 2.9e-5 (--elements 256 --euler-bernoulli --section-inertia-scale 1e-3
--newton-abs 1e-3 --check --compare tests/data/exudyn_ancf_150rad_s.csv). With the rotary
inertia kept the shear-rigid limit (extrapolated) is 2.2e-3 off, about a quarter of the shear
beam's 9.2e-3 (Timoshenko's frequency correction: rotary inertia 1 part, shear E / (k G) = 3.1
parts). The shear-rigid runs need --newton-abs 1e-3 from 256 elements.

Higher loads (--speed, --youngs-scale; the headers of the files hold the convergence numbers).
The rod's inertial axial load, of order m r W^2 (m the rod's mass), against its Euler load
pi^2 E I / L^2 = 1.75 kN: 0.26 kN at 150 rad/s, 1.04 kN at 300, 4.1 kN at 600; 0.26 kN against
17.5 N with E / 100.
- 300 rad/s, tests/data/exudyn_shear_beam_300rad_s.csv: peak |v_mid/L| 7.0e-2; 512 elements,
  h = 5e-7 s as at 150 rad/s (extrapolation in N 8e-5 of the peak off, h 1e-6 s 4e-5).
- 600 rad/s, tests/data/exudyn_shear_beam_600rad_s.csv: the rod buckles and folds: peak
  |v_mid/L| 0.41, the chord B -> C down to a quarter of L, the slider behind the crank centre
  (x down to -0.066 m) and the rod sweeping across the crank arm (no contact in this model). It
  converges all the same: 1024 elements, h = 2.5e-7 s (extrapolation in N 1.8e-4, h 5e-7 s
  1.7e-4; at 256 elements --newton-abs 1e-5 against 1e-4 moves v_mid by 5e-10 of its peak).
- 150 rad/s with E / 100 (--youngs-scale 0.01): no reference over two revolutions. The rod
  collapses (first |v_mid/L| maximum 0.34 at 15 ms, the slider behind the crank centre from
  15 ms, the chord down to 0.064 L and the rod crossing itself from 20 ms) and the run becomes
  chaotic: two 64-element runs that differ only in the Newton tolerance (absolute 1e-5 -> 1e-6,
  relative 1e-8 -> 1e-10) part by 1e-4 of the peak at 49 ms and by more than the peak later.
  The runs (h = 5e-7 s) agree to 1e-2 of the peak until 29 ms (128 against 256 elements) and
  32 ms (256 against 512), to 1e-1 until 33 and 41 ms. Over the early part, 0 .. 16 ms, it
  converges: tests/data/exudyn_shear_beam_e100_150rad_s.csv (--stop 0.016), 512 elements,
  h = 5e-7 s: |v_mid/L| first passes 0.25 at 10.3 ms (between the 10.3 and 10.4 ms samples) and
  reaches its window peak 0.345 at 15.1 ms; 256 elements 8.2e-5 of the peak v_mid off, the
  extrapolation in N 2.7e-5, h 1e-6 s 7.3e-7.

Columns (every --sample s, 0 .. --stop, by default two revolutions, 4 pi / W rounded up to the
sample grid: 0.0838 s at 150 rad/s), the columns and signs of
tests/data/exudyn_ancf_150rad_s.csv: t, v_mid/L (distance of the material midpoint from the
chord B->C, positive to the left, over L), the force of the rod on the crank pin (FBx, FBy) and
on the slider (FCx, FCy), N.

Convergence and comparison (printed and written to the CSV header): --check also runs half the
elements and twice the step and gives, for each column, the largest difference to this run over
this run's peak (absolute, N, for a column that is 0 throughout: FCx with no slider mass), and
the same for the extrapolation in N (this run + (this run - half the elements) / 3);
--compare FILE ... gives the same for this run (and the extrapolation) against each file (same
columns), over the file's peaks.

Usage (from the repository root, with exudyn installed from PyPI; about 6 minutes of CPU with
the two check runs):
  python tests/data/benchmark_shear_reference.py --elements 512 --step 5e-7 --newton-abs 1e-4 \\
      --check --compare tests/data/exudyn_ancf_150rad_s.csv \\
      --out tests/data/exudyn_shear_beam_150rad_s.csv
  python tests/data/benchmark_shear_reference.py --speed 300 --elements 512 --step 5e-7 \\
      --newton-abs 1e-4 --check --out tests/data/exudyn_shear_beam_300rad_s.csv
  python tests/data/benchmark_shear_reference.py --speed 600 --elements 1024 --step 2.5e-7 \\
      --newton-abs 1e-4 --check --out tests/data/exudyn_shear_beam_600rad_s.csv
  python tests/data/benchmark_shear_reference.py --youngs-scale 0.01 --speed 150 --stop 0.016 \\
      --elements 512 --step 5e-7 --newton-abs 1e-4 --check \\
      --out tests/data/exudyn_shear_beam_e100_150rad_s.csv
(3, 7 and about 1 minute of CPU).
"""

import argparse
import math
import sys
import time
import tomllib

import numpy as np
import exudyn as exu
from exudyn.itemInterface import (
    CoordinateConstraint,
    MarkerNodeCoordinate,
    MarkerNodePosition,
    MassPoint2D,
    NodePoint2D,
    NodePointGround,
    NodeRigidBody2D,
    ObjectBeamGeometricallyExact2D,
    ObjectJointRevolute2D,
    SensorNode,
    SensorObject,
)

W_DEFAULT = 150.0  # rad/s


def two_revolutions(w, sample):
    """Two revolutions, 4 pi / w, rounded up to the sample grid (0.0838 s at 150 rad/s)."""
    return round(math.ceil(4.0 * math.pi / w / sample - 1e-9) * sample, 12)

COLUMNS = ["t", "v_mid_rel", "FBx", "FBy", "FCx", "FCy"]


def read_csv(path):
    rows = [
        [float(x) for x in line.split(",")]
        for line in open(path)
        if line.strip() and not line.startswith("#") and not line.startswith("t")
    ]
    return np.array(rows)


def differences(rows, ref, sample):
    """Largest |difference| of each column at the common times over the column's peak in ref
    (absolute where that peak is 0), and the number of common times."""
    k_run = np.rint(rows[:, 0] / sample).astype(int)
    k_ref = np.rint(ref[:, 0] / sample).astype(int)
    common, i_run, i_ref = np.intersect1d(k_run, k_ref, return_indices=True)
    parts = []
    for c in range(1, len(COLUMNS)):
        peak = np.max(np.abs(ref[i_ref, c]))
        diff = np.max(np.abs(rows[i_run, c] - ref[i_ref, c]))
        parts.append(f"{COLUMNS[c]} {diff / peak:.1e}" if peak > 0 else f"{COLUMNS[c]} {diff:.0e} N")
    return ", ".join(parts), len(common)


def simulate(scene, n, step, args):
    """The run with n elements and step h: the rows (t, v_mid/L, FBx, FBy, FCx, FCy) and the CPU
    time of the integration, s."""
    rod = scene["rod"]
    W = args.speed
    r, length = scene["crank"]["length"], rod["length"]
    e_mod, rho = rod["youngs_modulus"] * args.youngs_scale, rod["density"]
    area, area_moment = rod["area"], rod["area_moment"]
    g_mod = e_mod / 2.6
    shear_area = area / 1.2
    m_s = scene.get("slider", {}).get("mass", 0.0)
    offset = scene.get("mechanism", {}).get("slider_offset", 0.0)
    assert offset == 0.0, "the reference places the rod along x at t = 0"
    assert n % 2 == 0
    h = length / n

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    # Rigid motion at theta = 0: pin B moves at (0, r W), pin C is at rest, the rod turns at
    # -r W / L.
    nodes = [
        mbs.AddNode(
            NodeRigidBody2D(
                referenceCoordinates=[r + i * h, 0.0, 0.0],
                initialVelocities=[0.0, r * W * (1.0 - i / n), -r * W / length],
            )
        )
        for i in range(n + 1)
    ]
    for i in range(n):
        mbs.AddObject(
            ObjectBeamGeometricallyExact2D(
                nodeNumbers=[nodes[i], nodes[i + 1]],
                length=h,
                massPerLength=rho * area,
                crossSectionInertia=rho * area_moment * args.section_inertia_scale,
                bendingStiffness=e_mod * area_moment,
                axialStiffness=e_mod * area,
                shearStiffness=g_mod * shear_area * (1e3 if args.euler_bernoulli else 1.0),
            )
        )
    m_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))

    def pin_x(mbs, t, item, off):
        return r * math.cos(W * t) - r

    def pin_y(mbs, t, item, off):
        return r * math.sin(W * t)

    pins = []
    for coord, fun in ((0, pin_x), (1, pin_y)):
        m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coord))
        pins.append(
            mbs.AddObject(
                CoordinateConstraint(markerNumbers=[m_ground, m], offsetUserFunction=fun)
            )
        )
    if m_s > 0.0:
        slider = mbs.AddNode(NodePoint2D(referenceCoordinates=[r + length, 0.0]))
        mbs.AddObject(MassPoint2D(nodeNumber=slider, mass=m_s))
        joint_c = mbs.AddObject(
            ObjectJointRevolute2D(
                markerNumbers=[
                    mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1])),
                    mbs.AddMarker(MarkerNodePosition(nodeNumber=slider)),
                ]
            )
        )
        m_sy = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=slider, coordinate=1))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_sy]))
        guide_c = None
    else:
        joint_c = None
        m_cy = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[-1], coordinate=1))
        guide_c = mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_cy]))

    def sensor(item):
        return mbs.AddSensor(item)

    mid = n // 2
    s_pos = [
        sensor(SensorNode(nodeNumber=nodes[i], outputVariableType=exu.OutputVariableType.Position,
                          storeInternal=True))
        for i in (0, mid, n)
    ]
    s_pin = [
        sensor(SensorObject(objectNumber=p, outputVariableType=exu.OutputVariableType.Force,
                            storeInternal=True))
        for p in pins
    ]
    s_c = sensor(SensorObject(objectNumber=joint_c if joint_c is not None else guide_c,
                              outputVariableType=exu.OutputVariableType.Force,
                              storeInternal=True))
    mbs.Assemble()

    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = int(round(args.stop / step))
    settings.timeIntegration.endTime = args.stop
    settings.timeIntegration.generalizedAlpha.spectralRadius = args.rho_inf
    settings.timeIntegration.adaptiveStep = False
    settings.timeIntegration.newton.relativeTolerance = args.newton_tol
    settings.timeIntegration.newton.absoluteTolerance = args.newton_abs
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.verboseMode = 0
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = args.sample
    settings.show.statistics = False
    start = time.process_time()
    try:
        ok = exu.SolveDynamic(mbs, settings, showHints=True)
    except exu.SolverError:
        ok = False
    elapsed = time.process_time() - start

    def data(s):
        return mbs.GetSensorStoredData(s)

    pb, pm, pc = (data(s) for s in s_pos)
    times = pb[:, 0]
    fbx, fby = data(s_pin[0]), data(s_pin[1])
    fc = data(s_c)
    rows = []
    for k, t in enumerate(times):
        grid = round(t / args.sample) * args.sample
        assert abs(t - grid) < 0.5 * step, f"sample at {t} off the {args.sample} s grid"
        b, m, c = pb[k, 1:3], pm[k, 1:3], pc[k, 1:3]
        chord, d = c - b, m - b
        v = (chord[0] * d[1] - chord[1] * d[0]) / math.hypot(*chord)
        # Signs: the constraint force of Exudyn's coordinate constraint is the force on the
        # node's coordinate with a minus sign, so the rod's force on the pin (and, with no
        # slider body, on the guide at C) is +lambda; the revolute joint's force acts on its
        # second marker (the slider) with a minus sign.
        if joint_c is not None:
            fcx, fcy = -fc[k, 1], -fc[k, 2]
        else:
            fcx, fcy = 0.0, fc[k, 1]
        rows.append((grid, v / length, fbx[k, 1], fby[k, 1], fcx, fcy))
    rows = np.array(rows)
    if not ok:
        sys.exit(
            f"{n} elements, h = {step:g} s: the solver failed at t = {rows[-1, 0]:g} s (last"
            f" sample) after {elapsed:.0f} s of CPU; max |v_mid/L| up to then"
            f" {np.max(np.abs(rows[:, 1])):.3e}"
        )
    print(
        f"{n} elements, h = {step:g} s: {elapsed:.1f} s of CPU, max |v_mid/L| "
        f"{np.max(np.abs(rows[:, 1])):.4e}",
        file=sys.stderr,
    )
    assert np.all(np.diff(rows[:, 0]) > 0.5 * args.sample), "sensor samples not one per grid point"
    return rows, elapsed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="scenes/benchmark.toml")
    ap.add_argument("--elements", type=int, default=512)
    ap.add_argument("--step", type=float, default=5e-7)
    ap.add_argument("--sample", type=float, default=1e-4)
    ap.add_argument("--rho-inf", type=float, default=0.9)
    ap.add_argument("--newton-tol", type=float, default=1e-8)
    ap.add_argument("--newton-abs", type=float, default=1e-4)
    ap.add_argument("--speed", type=float, default=W_DEFAULT, help="constant crank speed W, rad/s")
    ap.add_argument(
        "--youngs-scale",
        type=float,
        default=1.0,
        help="factor on the scene's Young's modulus E (G = E / 2.6 follows)",
    )
    ap.add_argument(
        "--stop",
        type=float,
        default=None,
        help="end time, s; default two revolutions, 4 pi / W rounded up to the --sample grid",
    )
    ap.add_argument(
        "--euler-bernoulli",
        action="store_true",
        help="shear stiffness x 1e3 (no shear deformation; section rotary inertia kept)",
    )
    ap.add_argument(
        "--section-inertia-scale",
        type=float,
        default=1.0,
        help="factor on the cross-section inertia rho I (1e-3 with --euler-bernoulli: the cable)",
    )
    ap.add_argument(
        "--out",
        default=None,
        help="default tests/data/exudyn_shear_beam_<W>rad_s.csv (_E<F> added for --youngs-scale F)",
    )
    ap.add_argument(
        "--check",
        action="store_true",
        help="also run half the elements and twice the step; their differences go to the header",
    )
    ap.add_argument("--compare", nargs="*", default=[], help="reference files (same columns)")
    args = ap.parse_args()
    if args.stop is None:
        args.stop = two_revolutions(args.speed, args.sample)
    if args.out is None:
        args.out = f"tests/data/exudyn_shear_beam_{args.speed:g}rad_s" + (
            f"_E{args.youngs_scale:g}" if args.youngs_scale != 1.0 else ""
        ) + ".csv"
    with open(args.scene, "rb") as f:
        scene = tomllib.load(f)
    m_s = scene.get("slider", {}).get("mass", 0.0)
    n = args.elements
    rows, elapsed = simulate(scene, n, args.step, args)
    notes = []
    extrapolated = None
    if args.check:
        for n_c, h_c in ((n // 2, args.step), (n, 2.0 * args.step)):
            other, t_c = simulate(scene, n_c, h_c, args)
            elapsed += t_c
            diff, _ = differences(other, rows, args.sample)
            notes.append(
                f"{n_c} elements, h = {h_c:g} s against this run, max |d| / max |this|: {diff}"
            )
            if n_c < n:
                # Richardson: the elements' error goes as 1/N^2.
                extrapolated = rows + (rows - other) / 3.0
                extrapolated[:, 0] = rows[:, 0]
                diff, _ = differences(extrapolated, rows, args.sample)
                notes.append(f"extrapolation in N against this run: {diff}")
    for path in args.compare:
        ref = read_csv(path)
        diff, count = differences(rows, ref, args.sample)
        name = path.rsplit("/", 1)[-1]
        notes.append(f"this run against {name} ({count} times), max |d| / max |that|: {diff}")
        if extrapolated is not None:
            diff, _ = differences(extrapolated, ref, args.sample)
            notes.append(f"extrapolation in N against {name}: {diff}")
    e_scaled = scene["rod"]["youngs_modulus"] * args.youngs_scale
    slider_line = (
        "slider mass 0: the last node's y held at 0 by a coordinate constraint, no slider body"
        if m_s == 0.0
        else f"slider: mass point {m_s:g} kg, revolute joint to the last node"
    )
    header = (
        "# Shear-deformable reference, CDI benchmark rod (scenes/benchmark.toml) at a constant "
        f"{args.speed:g} rad/s\n"
        "# from t = 0, undeformed start moving rigidly with the crank; G = E / 2.6, shear area A / 1.2,\n"
        f"# section inertia rho I, no damping;\n# {slider_line}.\n"
        f"# Exudyn {exu.config.Version()} ObjectBeamGeometricallyExact2D, {n} elements, generalized-alpha\n"
        f"# (spectral radius {args.rho_inf}), h = {args.step:g} s; {elapsed:.0f} s of CPU"
        + (" with the two check runs" if args.check else "")
        + ".\n"
        + (
            f"# Young's modulus x {args.youngs_scale:g}: E = {e_scaled:.6g} Pa, G = E / 2.6.\n"
            if args.youngs_scale != 1.0
            else ""
        )
        + ("# Shear-rigid limit: shear stiffness x 1e3.\n" if args.euler_bernoulli else "")
        + (
            f"# Cross-section inertia x {args.section_inertia_scale:g}.\n"
            if args.section_inertia_scale != 1.0
            else ""
        )
        + "".join(f"# {note}\n" for note in notes)
        + "# Columns and signs of exudyn_ancf_150rad_s.csv. A development cross-check only.\n"
        "# Command: python tests/data/benchmark_shear_reference.py " + " ".join(sys.argv[1:]) + "\n"
        + ",".join(COLUMNS) + "\n"
    )
    with open(args.out, "w") as f:
        f.write(header)
        for row in rows:
            f.write(f"{row[0]:.6e},{row[1]:.9e}," + ",".join(f"{x:.7e}" for x in row[2:]) + "\n")
    print(f"{len(rows)} rows to {args.out}, {elapsed:.1f} s of CPU", file=sys.stderr)
    for note in notes:
        print(note)


if __name__ == "__main__":
    main()
