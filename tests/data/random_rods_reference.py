"""Independent reference for random uniform rods in the slider-crank: Exudyn's geometrically
exact, shear-deformable 2D beam (ObjectBeamGeometricallyExact2D, Simo-Reissner, linear elements),
converged in space and time, for a test that runs the default FMU with only physical parameters
changed and compares `rod.deflection_rel` and the pin forces.

The rods (seeded, `numpy.random.default_rng(seed)`: first the order of the materials, the rods
with end bodies and those without slider mass, then for each rod its draws in this order):
- uniform rectangular section: L ~ U[0.1, 0.6] m; slenderness L/h log-uniform in [8, 60] (h in
  the plane of motion); width b = h U[0.4, 1.0]; A = b h, I = b h^3 / 12; shear area A / 1.2;
  G = E / 2.6.
- material: steel (E 2.1e11 Pa, rho 7850 kg/m3), aluminium (7.0e10, 2700), titanium (1.1e11,
  4430), or a soft composite (E log-uniform in [5e9, 3e10], rho U[1400, 2000]); a third of the
  rods (rounded) are soft, the rest cycle through the three metals, in a seeded random order.
- crank r = L U[0.2, 0.4]; rod mass m = rho A L; slider mass m U[0, 2], exactly 0 on one rod in
  eight (seeded choice); end bodies on half of the rods (seeded choice): big end mass m U[0, 0.8]
  with inertia about B mass (U[0.5, 1.5] h)^2, small end mass m U[0, 0.4] with inertia about C
  mass (U[0.5, 1.5] h)^2; the others have none (0).
- no gravity, no slider offset, no slider force, no damping.

The run protocol (what the FMU test reproduces):
- even ids start smoothly, odd ids abruptly; T_rev = 2 pi / W; communication step
  dt = T_rev / 400.
  smooth: start at rest, undeformed, crank at theta = 0; omega = W (1 - cos(pi t / T)) / 2 for
    t < T = T_rev, then W; stop at 3 T_rev.
  abrupt: omega = W from t = 0, theta = W t; stop at 2 T_rev. The rod starts undeformed on the
    chord, moving rigidly with the crank: the node at arc length s has velocity
    (0, r W (1 - s / L)) and rotation rate -r W / L, the slider is at rest (the velocities the
    constraints impose on a rigid rod at theta = 0).
  The FMU is driven at the communication points t_k = k dt with theta_k, omega_k and the crank
  acceleration alpha_k (crank.angle, crank.speed and the derivative of crank.speed) and follows
  within each step the quadratic theta_k + omega_k s + alpha_k s^2 / 2. Pin B of the reference
  follows the drive law itself: for the abrupt start the two are identical (alpha = 0); during
  the smooth ramp the quadratic ends each step off the law by at most jerk dt^3 / 6 (8.1e-8 rad)
  in angle and jerk dt^2 / 2 (1.5e-5 W) in speed, and these jumps, imposed on a position
  constraint, make the integrator's constraint forces alternate from step to step (on a slender
  rod by three times the peak pin force, spectral radius 0.95) without converging as h -> 0,
  while v_mid / L moves by 4e-6 relative (spectral radius 0.5, where the alternation is damped).
  --step-law runs the per-step quadratic instead.
- W is chosen so that the peak |v_mid / L| reaches a target drawn log-uniform in [2e-3, 3e-2]:
  first from the quasi-static midpoint deflection under the triangular inertia load
  q0 = rho A r W^2 (v_mid = 5 q0 L^4 / (768 E I)), then corrected once by sqrt(target / peak)
  with the peak of a coarse run; W is capped at 3000 rad/s and at a quarter of the first
  pinned-pinned bending frequency (sqrt(E I / (rho A)) (pi / L)^2), so that large targets on
  stiff or slender rods are not reached (target_peak and peak_v_rel both recorded).
- the beam: n elements of equal length, pin B's x and y prescribed (coordinate constraints), the
  slider a mass point on y = 0 pinned to the last node (revolute joint), end bodies as
  ObjectRigidBody2D on the end nodes (mass at the node, inertia about it). Generalized-alpha
  (spectral radius --rho-inf), constant step h = dt / m.
- converged: every rod runs at (n, m) and (2 n, 2 m); the finer is stored, and the differences
  between the two, max |dv| / max |v| over v_mid / L and max |dF| / max |F| over the four pin
  force components together, are recorded (conv_v, conv_f). Defaults: smooth n = 128, m = 4;
  abrupt n = 128, m = 32. The abrupt start rings the rod's axial and bending modes, undamped:
  v_mid / L needs the finer mesh (the phase of the bending ringing), and the pin forces carry
  steep axial wave fronts whose maxima converge slowly (conv_f of a few percent).
- the sensors are written every 2 dt (checked: the stored times are k 2 dt to 1e-12 of t_stop);
  the Newton absolute tolerance is 1e-6 of the crank's inertia force (total mass r W^2).

Output in --out-dir:
- rods.csv: one row per rod (header lines start with #): id, start (smooth|abrupt), W (rad/s),
  t_ramp (s, 0 for abrupt), t_stop (s), dt_comm (s), crank_length, rod_length (m),
  youngs_modulus (Pa), density (kg/m3), area (m2), area_moment (m4), height, width (m),
  shear_modulus (Pa), shear_area (m2), slider_mass, big_end_mass (kg), big_end_inertia (kg m2,
  about B), small_end_mass (kg), small_end_inertia (kg m2, about C), rod_mass (kg), f1_hz
  (pinned-pinned Euler-Bernoulli first bending frequency), material, slenderness (L/h),
  target_peak, peak_v_rel (max |v_mid / L| of the stored run), elements, step (s), conv_v,
  conv_f, cpu_s (both resolutions and the coarse run).
- rod_NN.csv (NN = id): t, v_mid_rel, FBx, FBy, FCx, FCy at every second communication point
  from t = 0 (t = k 2 dt). v_mid / L: distance of the material midpoint from the chord B->C,
  positive to the left, over L; (FBx, FBy) the force of the rod on the crank pin, (FCx, FCy) the
  force of the rod on the slider, global frame, N (the conventions of
  tests/data/automotive_reference.py).

Usage (from the repository root, with the packages of tests/data/requirements-reference.txt):
  python tests/data/random_rods_reference.py
  python tests/data/random_rods_reference.py --only 3 --out-dir /tmp/rods   # one rod
"""

import argparse
import math
import os
import sys
import time

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
    ObjectRigidBody2D,
    SensorNode,
    SensorObject,
)

MATERIALS = {
    "steel": (2.1e11, 7850.0),
    "aluminium": (7.0e10, 2700.0),
    "titanium": (1.1e11, 4430.0),
}
W_CAP = 3000.0  # rad/s
COMM_PER_REV = 400
SAMPLE_EVERY = 2  # communication steps between stored rows


def draw_rods(seed, n_rods):
    rng = np.random.default_rng(seed)
    n_soft = int(round(n_rods / 3))
    metals = list(MATERIALS)
    kinds = ["soft"] * n_soft + [metals[i % 3] for i in range(n_rods - n_soft)]
    kinds = [kinds[i] for i in rng.permutation(n_rods)]
    ends = set(rng.permutation(n_rods)[: n_rods // 2].tolist())
    no_slider = set(rng.permutation(n_rods)[: int(round(n_rods / 8))].tolist())
    rods = []
    for i in range(n_rods):
        length = rng.uniform(0.1, 0.6)
        slender = math.exp(rng.uniform(math.log(8.0), math.log(60.0)))
        height = length / slender
        width = height * rng.uniform(0.4, 1.0)
        if kinds[i] == "soft":
            e_mod = math.exp(rng.uniform(math.log(5e9), math.log(3e10)))
            rho = rng.uniform(1400.0, 2000.0)
        else:
            e_mod, rho = MATERIALS[kinds[i]]
        r = length * rng.uniform(0.2, 0.4)
        area = width * height
        moment = width * height**3 / 12.0
        m = rho * area * length
        u_slider = rng.uniform(0.0, 2.0)
        u_big, k_big, u_small, k_small = (
            rng.uniform(0.0, 0.8),
            rng.uniform(0.5, 1.5),
            rng.uniform(0.0, 0.4),
            rng.uniform(0.5, 1.5),
        )
        target = math.exp(rng.uniform(math.log(2e-3), math.log(3e-2)))
        big = (m * u_big, m * u_big * (k_big * height) ** 2) if i in ends else (0.0, 0.0)
        small = (m * u_small, m * u_small * (k_small * height) ** 2) if i in ends else (0.0, 0.0)
        omega1 = math.sqrt(e_mod * moment / (rho * area)) * (math.pi / length) ** 2
        rods.append(
            dict(
                id=i,
                start="smooth" if i % 2 == 0 else "abrupt",
                material=kinds[i],
                crank_length=r,
                rod_length=length,
                youngs_modulus=e_mod,
                density=rho,
                area=area,
                area_moment=moment,
                height=height,
                width=width,
                shear_modulus=e_mod / 2.6,
                shear_area=area / 1.2,
                slider_mass=0.0 if i in no_slider else m * u_slider,
                big_end_mass=big[0],
                big_end_inertia=big[1],
                small_end_mass=small[0],
                small_end_inertia=small[1],
                rod_mass=m,
                f1_hz=omega1 / (2.0 * math.pi),
                slenderness=slender,
                target_peak=target,
            )
        )
    return rods


def w_limit(rod):
    return min(W_CAP, 2.0 * math.pi * rod["f1_hz"] / 4.0)


def w_quasi_static(rod):
    """W for which 5 q0 L^4 / (768 E I) / L = target, q0 = rho A r W^2."""
    r, length = rod["crank_length"], rod["rod_length"]
    ei, rho_a = rod["youngs_modulus"] * rod["area_moment"], rod["density"] * rod["area"]
    return math.sqrt(rod["target_peak"] * 768.0 * ei / (5.0 * rho_a * r * length**3))


class Drive:
    def __init__(self, start, w, step_law=False):
        self.start, self.w, self.step_law = start, w, step_law
        self.t_rev = 2.0 * math.pi / w
        self.dt = self.t_rev / COMM_PER_REV
        self.t_ramp = self.t_rev if start == "smooth" else 0.0
        self.n_comm = COMM_PER_REV * (3 if start == "smooth" else 2)
        self.t_stop = self.n_comm * self.dt

    def law(self, t):
        """(theta, omega, alpha) of the drive at t."""
        w, tr = self.w, self.t_ramp
        if t < tr and tr > 0.0:
            x = math.pi * t / tr
            return (
                0.5 * w * (t - tr / math.pi * math.sin(x)),
                0.5 * w * (1.0 - math.cos(x)),
                0.5 * w * math.pi / tr * math.sin(x),
            )
        return (0.5 * w * tr + w * (t - tr), w, 0.0)

    def crank_angle(self, t):
        """The crank angle the beam's pin follows (see step_angle)."""
        return self.step_angle(t) if self.step_law else self.law(t)[0]

    def step_angle(self, t):
        """The per-step quadratic from the input at t_k, t in (t_k, t_k + dt]."""
        k = max(0, math.ceil(t / self.dt - 1e-7) - 1)
        tk = k * self.dt
        th, om, al = self.law(tk)
        s = t - tk
        return th + om * s + 0.5 * al * s * s


def simulate(rod, drive, n, m, rho_inf, stop=None):
    """Runs the rod; returns (t, [v_rel, FBx, FBy, FCx, FCy] columns, cpu seconds)."""
    r, length = rod["crank_length"], rod["rod_length"]
    e_mod, rho, g_mod = rod["youngs_modulus"], rod["density"], rod["shear_modulus"]
    area, moment, a_s = rod["area"], rod["area_moment"], rod["shear_area"]
    assert n % 2 == 0
    he = length / n
    abrupt = drive.start == "abrupt"
    w = drive.w

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    nodes = []
    for i in range(n + 1):
        s = i * he
        v0 = [0.0, r * w * (1.0 - s / length), -r * w / length] if abrupt else [0.0, 0.0, 0.0]
        nodes.append(
            mbs.AddNode(
                NodeRigidBody2D(referenceCoordinates=[r + s, 0.0, 0.0], initialVelocities=v0)
            )
        )
    for i in range(n):
        mbs.AddObject(
            ObjectBeamGeometricallyExact2D(
                nodeNumbers=[nodes[i], nodes[i + 1]],
                length=he,
                massPerLength=rho * area,
                crossSectionInertia=rho * moment,
                bendingStiffness=e_mod * moment,
                axialStiffness=e_mod * area,
                shearStiffness=g_mod * a_s,
            )
        )
    for node, key in ((nodes[0], "big_end"), (nodes[-1], "small_end")):
        if rod[key + "_mass"] > 0.0:
            mbs.AddObject(
                ObjectRigidBody2D(
                    nodeNumber=node, mass=rod[key + "_mass"], inertia=rod[key + "_inertia"]
                )
            )
    slider = mbs.AddNode(NodePoint2D(referenceCoordinates=[r + length, 0.0]))
    mbs.AddObject(MassPoint2D(nodeNumber=slider, mass=rod["slider_mass"]))
    joint_c = mbs.AddObject(
        ObjectJointRevolute2D(
            markerNumbers=[
                mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1])),
                mbs.AddMarker(MarkerNodePosition(nodeNumber=slider)),
            ]
        )
    )
    m_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))

    def pin_x(mbs, t, item, off):
        return r * math.cos(drive.crank_angle(t)) - r

    def pin_y(mbs, t, item, off):
        return r * math.sin(drive.crank_angle(t))

    # The initial velocities satisfy the constraints: pin B's from the drive law (central
    # difference), the last node's (0, 0) is the slider's, which starts at rest on y = 0.
    eps = 1e-6 * drive.dt
    for fun, v0 in ((pin_x, 0.0), (pin_y, r * w if abrupt else 0.0)):
        rate = (fun(mbs, eps, 0, 0.0) - fun(mbs, -eps, 0, 0.0)) / (2.0 * eps)
        assert abs(rate - v0) <= 1e-6 * max(r * w, 1e-300), (rate, v0)
    pins = []
    for coord, fun in ((0, pin_x), (1, pin_y)):
        mk = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coord))
        pins.append(
            mbs.AddObject(
                CoordinateConstraint(markerNumbers=[m_ground, mk], offsetUserFunction=fun)
            )
        )
    m_sy = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=slider, coordinate=1))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_sy]))

    def force_sensor(obj):
        return mbs.AddSensor(
            SensorObject(
                objectNumber=obj, outputVariableType=exu.OutputVariableType.Force, storeInternal=True
            )
        )

    s_pos = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=nodes[i],
                outputVariableType=exu.OutputVariableType.Position,
                storeInternal=True,
            )
        )
        for i in (0, n // 2, n)
    ]
    s_pin = [force_sensor(p) for p in pins]
    s_joint = force_sensor(joint_c)
    mbs.Assemble()

    stop = drive.t_stop if stop is None else stop
    n_steps = int(round(stop / drive.dt)) * m
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = n_steps
    settings.timeIntegration.endTime = stop
    settings.timeIntegration.generalizedAlpha.spectralRadius = rho_inf
    settings.timeIntegration.adaptiveStep = False
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    settings.timeIntegration.newton.relativeTolerance = 1e-8
    # Residuals are forces: the absolute tolerance is relative to the inertia forces of the
    # crank motion, the round-off floor of the stiff axial terms lies below it.
    masses = rod["rod_mass"] + rod["slider_mass"] + rod["big_end_mass"] + rod["small_end_mass"]
    settings.timeIntegration.newton.absoluteTolerance = 1e-6 * masses * r * w * w
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.verboseMode = int(os.environ.get("RR_VERBOSE", "0"))
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = SAMPLE_EVERY * drive.dt
    settings.show.statistics = False
    start = time.process_time()
    exu.SolveDynamic(mbs, settings, showHints=True)
    cpu = time.process_time() - start

    def data(s):
        return mbs.GetSensorStoredData(s)

    pb, pm, pc = (data(s) for s in s_pos)
    times = pb[:, 0]
    expect = np.arange(len(times)) * SAMPLE_EVERY * drive.dt
    n_rows = int(round(stop / drive.dt / SAMPLE_EVERY)) + 1
    if len(times) != n_rows or np.max(np.abs(times - expect)) > 1e-12 * stop:
        raise RuntimeError(
            f"sensor times off the grid: {len(times)} rows (expected {n_rows}), "
            f"max |t - k 2 dt| = {np.max(np.abs(times[:min(len(times), n_rows)] - expect[:min(len(times), n_rows)])):.3e}"
        )
    chord = pc[:, 1:3] - pb[:, 1:3]
    d = pm[:, 1:3] - pb[:, 1:3]
    v = (chord[:, 0] * d[:, 1] - chord[:, 1] * d[:, 0]) / np.hypot(chord[:, 0], chord[:, 1])
    fbx, fby, fj = data(s_pin[0]), data(s_pin[1]), data(s_joint)
    # Signs: the rod's force on the pin is +lambda of the coordinate constraint; the revolute
    # joint's force acts on its second marker (the slider) with a minus sign.
    cols = np.column_stack([v / length, fbx[:, 1], fby[:, 1], -fj[:, 1], -fj[:, 2]])
    return expect, cols, cpu


def conv(fine, coarse):
    dv = np.max(np.abs(fine[:, 0] - coarse[:, 0])) / np.max(np.abs(fine[:, 0]))
    df = np.max(np.abs(fine[:, 1:] - coarse[:, 1:])) / np.max(np.abs(fine[:, 1:]))
    return dv, df


COLUMNS = [
    "id", "start", "W", "t_ramp", "t_stop", "dt_comm", "crank_length", "rod_length",
    "youngs_modulus", "density", "area", "area_moment", "height", "width", "shear_modulus",
    "shear_area", "slider_mass", "big_end_mass", "big_end_inertia", "small_end_mass",
    "small_end_inertia", "rod_mass", "f1_hz", "material", "slenderness", "target_peak",
    "peak_v_rel", "elements", "step", "conv_v", "conv_f", "cpu_s",
]  # fmt: skip


def fmt(x):
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)):
        return str(x)
    return f"{x:.10g}"


def main():
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="The protocol, the columns and the usage: see the module docstring.",
    )
    ap.add_argument("--seed", type=int, default=20261125, help="seed of numpy's default_rng")
    ap.add_argument("--rods", type=int, default=44, help="number of rods")
    ap.add_argument("--only", type=int, nargs="*", help="run only these ids (rods.csv not written)")
    ap.add_argument(
        "--elements-smooth",
        type=int,
        default=128,
        help="elements n of the coarser run, smooth start (the stored run: 2 n)",
    )
    ap.add_argument(
        "--elements-abrupt",
        type=int,
        default=128,
        help="elements n of the coarser run, abrupt start (the stored run: 2 n)",
    )
    ap.add_argument(
        "--substeps-smooth",
        type=int,
        default=4,
        help="steps m per communication step of the coarser run, smooth start (stored: 2 m)",
    )
    ap.add_argument(
        "--substeps-abrupt",
        type=int,
        default=32,
        help="steps m per communication step of the coarser run, abrupt start (stored: 2 m)",
    )
    ap.add_argument("--rho-inf", type=float, default=0.95, help="generalized-alpha spectral radius")
    ap.add_argument(
        "--no-correct", action="store_true", help="keep the quasi-static W (no coarse run)"
    )
    ap.add_argument(
        "--step-law",
        action="store_true",
        help="pin B follows the per-step quadratic instead of the drive law (see the docstring)",
    )
    ap.add_argument("--out-dir", default="tests/data/random_rods")
    args = ap.parse_args()
    rods = draw_rods(args.seed, args.rods)
    ids = args.only if args.only else range(args.rods)
    os.makedirs(args.out_dir, exist_ok=True)
    command = " ".join(["python tests/data/random_rods_reference.py"] + sys.argv[1:])
    total = 0.0
    for i in ids:
        rod = rods[i]
        smooth = rod["start"] == "smooth"
        n = args.elements_smooth if smooth else args.elements_abrupt
        m = args.substeps_smooth if smooth else args.substeps_abrupt
        cpu = 0.0
        w = min(w_quasi_static(rod), w_limit(rod))
        if not args.no_correct:
            drive = Drive(rod["start"], w, args.step_law)
            _, cols, c = simulate(rod, drive, 16, max(4, m // 4), args.rho_inf)
            cpu += c
            peak = np.max(np.abs(cols[:, 0]))
            w = min(w * math.sqrt(rod["target_peak"] / peak), w_limit(rod))
        drive = Drive(rod["start"], w, args.step_law)
        t, coarse, c1 = simulate(rod, drive, n, m, args.rho_inf)
        t, fine, c2 = simulate(rod, drive, 2 * n, 2 * m, args.rho_inf)
        cpu += c1 + c2
        total += cpu
        dv, df = conv(fine, coarse)
        rod.update(
            W=w,
            t_ramp=drive.t_ramp,
            t_stop=drive.t_stop,
            dt_comm=drive.dt,
            peak_v_rel=float(np.max(np.abs(fine[:, 0]))),
            elements=2 * n,
            step=drive.dt / (2 * m),
            conv_v=dv,
            conv_f=df,
            cpu_s=cpu,
        )
        print(
            f"rod {i:2d} {rod['start']:6s} {rod['material']:9s} L/h {rod['slenderness']:5.1f} "
            f"W {w:7.1f} target {rod['target_peak']:.2e} peak {rod['peak_v_rel']:.2e} "
            f"conv_v {dv:.1e} conv_f {df:.1e} cpu {cpu:.1f} s",
            flush=True,
        )
        with open(os.path.join(args.out_dir, f"rod_{i:02d}.csv"), "w") as f:
            f.write(
                f"# Random rod {i} ({rod['start']} start, parameters in rods.csv): Exudyn "
                f"{exu.config.Version()} ObjectBeamGeometricallyExact2D, {2 * n} elements,\n"
                f"# generalized-alpha (spectral radius {args.rho_inf}), h = dt_comm / {2 * m}; pin B on\n"
                f"# {'the per-step quadratic' if args.step_law else 'the drive law'}.\n"
                f"# Command: {command}\n"
                "t,v_mid_rel,FBx,FBy,FCx,FCy\n"
            )
            for tk, row in zip(t, fine):
                f.write(f"{tk:.15g}," + ",".join(f"{x + 0.0:.8g}" for x in row) + "\n")
    print(f"total CPU {total:.1f} s", flush=True)
    if args.only:
        return
    with open(os.path.join(args.out_dir, "rods.csv"), "w") as f:
        f.write(
            f"# Random rods (seed {args.seed}) for the FMU reference test; see the docstring of\n"
            "# tests/data/random_rods_reference.py for the protocol. Units SI: W rad/s, times s,\n"
            "# lengths m, moduli Pa, density kg/m3, area m2, area_moment m4, masses kg,\n"
            "# inertias kg m2 (about the end node), f1_hz Hz (pinned-pinned Euler-Bernoulli),\n"
            "# target_peak / peak_v_rel: aimed and reached max |v_mid / L|, elements and step of the\n"
            "# stored run, conv_v / conv_f: max |dv| / max |v| and max |dF| / max |F| between the\n"
            "# stored run and one with half the elements and twice the step, cpu_s: CPU seconds.\n"
            f"# Exudyn {exu.config.Version()}, numpy {np.__version__}. Total CPU {total:.0f} s.\n"
            f"# Command: {command}\n"
        )
        f.write(",".join(COLUMNS) + "\n")
        for rod in rods:
            f.write(",".join(fmt(rod[c]) for c in COLUMNS) + "\n")


if __name__ == "__main__":
    main()
