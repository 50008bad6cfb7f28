"""Independent reference for the automotive rod (scenes/automotive_rod.toml): Exudyn's
geometrically exact, shear-deformable 2D beam (ObjectBeamGeometricallyExact2D, Simo-Reissner,
linear elements) in the slider-crank, for tests/automotive_reference.rs.

The run (the same in the Rust test, `tests/automotive_reference.rs`):
- crank radius r, rod length L, the rod's section table, end bodies, slider mass, E, G, rho read
  from the scene; shear area = area / 1.2 where the table gives none (as `rod::spec`);
  no damping (the Rust runs set rod.damping_ratio = 0).
- start at rest, undeformed, crank at theta = 0; the crank speed ramps smoothly to W = 628.3
  rad/s over T = 40 ms (`drive::CrankDrive::Ramp`: omega = W (1 - cos(pi t / T)) / 2), then stays
  at W for two revolutions (t = 40 .. 60 ms). As in the FMU, the crank law within each
  communication step [t_k, t_k + dt] (dt = 1e-5 s) is the quadratic from the input at t_k:
  theta = theta_k + omega_k s + alpha_k s^2 / 2.
- gas force on the slider (towards the crank), constant over each communication step at its
  value at the step's mid-time: F = -38 kN exp(-((theta - theta_f) / 20 deg)^2), theta_f = 4 pi
  + 15 deg (firing 15 degrees after the first top dead centre at full speed), the pulse of
  tests/real_rod_mechanics.rs.
- the beam: N elements of equal length, each with the section properties at its midpoint
  (area, area moment linear between stations: the element's mean); mass per length rho A,
  cross-section inertia rho I, EI, EA, G A_s. End bodies: ObjectRigidBody2D on the end nodes
  (mass at the node, inertia about it). Slider: a mass point on y = slider_offset, pinned to the
  last node by a revolute joint. Pin B: the first node's x and y prescribed (coordinate
  constraints). Generalized-alpha (spectral radius 0.9), step h.

Columns (every `--sample` s): t, v_mid/L (distance of the material midpoint from the chord B->C,
positive to the left, over L), the force of the rod on the crank pin (FBx, FBy) and on the
slider (FCx, FCy), N, the axial force N_mid (tension positive) and bending moment M_mid
(positive when it bends the rod towards +v, = EI kappa) at L/2 (mean of the two elements that
meet there: each element's strain is constant), N and N m, and the stress at L/2,
|N|/A + |M| c/I, Pa.

Usage (from the repository root, with exudyn installed from PyPI):
  python tests/data/automotive_reference.py --elements 64 --step 5e-7 \
      --out tests/data/exudyn_automotive_rod.csv
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
    LoadForceVector,
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
    SensorBody,
)

W = 628.3  # rad/s
T_RAMP = 0.04  # s
T_STOP = 0.06  # s
DT_COMM = 1e-5  # s: communication step of the Rust runs (input law and gas force per step)
GAS_PEAK = 38.0e3  # N
GAS_WIDTH = math.radians(20.0)
GAS_ANGLE = 4.0 * math.pi + math.radians(15.0)


def ramp(t):
    """drive::CrankDrive::Ramp at t: (theta, omega, alpha)."""
    if t < T_RAMP:
        x = math.pi * t / T_RAMP
        return (
            0.5 * W * (t - T_RAMP / math.pi * math.sin(x)),
            0.5 * W * (1.0 - math.cos(x)),
            0.5 * W * math.pi / T_RAMP * math.sin(x),
        )
    return (0.5 * W * T_RAMP + W * (t - T_RAMP), W, 0.0)


def step_index(t):
    """The communication step k with t in (t_k, t_k + dt] (k = 0 at t = 0)."""
    return max(0, math.ceil(t / DT_COMM - 1e-7) - 1)


def crank_angle(t):
    k = step_index(t)
    tk = k * DT_COMM
    th, om, al = ramp(tk)
    s = t - tk
    return th + om * s + 0.5 * al * s * s


def gas(theta):
    d = (theta - GAS_ANGLE) / GAS_WIDTH
    return -GAS_PEAK * math.exp(-d * d)


def gas_force(t):
    k = step_index(t)
    return gas(ramp((k + 0.5) * DT_COMM)[0])


def interp(table, key, s):
    pos = [st["position"] for st in table]
    return float(np.interp(s, pos, [st[key] for st in table]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="scenes/automotive_rod.toml")
    ap.add_argument("--elements", type=int, default=64)
    ap.add_argument("--step", type=float, default=5e-7)
    ap.add_argument("--sample", type=float, default=2e-5)
    ap.add_argument("--rho-inf", type=float, default=0.9)
    ap.add_argument(
        "--euler-bernoulli",
        action="store_true",
        help="shear stiffness x 1e3 (no shear deformation: the segment chain's physics)",
    )
    ap.add_argument("--newton-tol", type=float, default=1e-8)
    ap.add_argument("--newton-abs", type=float, default=1e-6)
    ap.add_argument("--stop", type=float, default=T_STOP)
    ap.add_argument("--out", default="tests/data/exudyn_automotive_rod.csv")
    args = ap.parse_args()
    with open(args.scene, "rb") as f:
        scene = tomllib.load(f)
    rod, table = scene["rod"], scene["rod"]["section"]
    r, length = scene["crank"]["length"], rod["length"]
    e_mod, rho, g_mod = rod["youngs_modulus"], rod["density"], rod["shear_modulus"]
    m_s = scene["slider"]["mass"]
    offset = scene.get("mechanism", {}).get("slider_offset", 0.0)
    assert offset == 0.0, "the reference places the rod along x at t = 0"
    n = args.elements
    assert n % 2 == 0
    h = length / n

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    nodes = [
        mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[r + i * h, 0.0, 0.0]))
        for i in range(n + 1)
    ]
    elements = []
    for i in range(n):
        s = (i + 0.5) * h
        a = interp(table, "area", s)
        ii = interp(table, "area_moment", s)
        a_s = interp(table, "shear_area", s) if "shear_area" in table[0] else a / 1.2
        elements.append(
            mbs.AddObject(
                ObjectBeamGeometricallyExact2D(
                    nodeNumbers=[nodes[i], nodes[i + 1]],
                    length=h,
                    massPerLength=rho * a,
                    crossSectionInertia=rho * ii,
                    bendingStiffness=e_mod * ii,
                    axialStiffness=e_mod * a,
                    shearStiffness=g_mod * a_s * (1e3 if args.euler_bernoulli else 1.0),
                )
            )
        )
    for node, key in ((nodes[0], "big_end"), (nodes[-1], "small_end")):
        body = rod.get(key)
        if body:
            mbs.AddObject(
                ObjectRigidBody2D(nodeNumber=node, mass=body["mass"], inertia=body["inertia"])
            )
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
    m_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))

    def pin_x(mbs, t, item, off):
        return r * math.cos(crank_angle(t)) - r

    def pin_y(mbs, t, item, off):
        return r * math.sin(crank_angle(t))

    pins = []
    for coord, fun in ((0, pin_x), (1, pin_y)):
        m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coord))
        pins.append(
            mbs.AddObject(
                CoordinateConstraint(markerNumbers=[m_ground, m], offsetUserFunction=fun)
            )
        )
    m_sy = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=slider, coordinate=1))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_sy]))
    mbs.AddLoad(
        LoadForceVector(
            markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=slider)),
            loadVector=[0, 0, 0],
            loadVectorUserFunction=lambda mbs, t, load: [gas_force(t), 0.0, 0.0],
        )
    )

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
    s_joint = sensor(SensorObject(objectNumber=joint_c,
                                  outputVariableType=exu.OutputVariableType.Force,
                                  storeInternal=True))
    s_sec = [
        sensor(SensorBody(bodyNumber=elements[e], localPosition=[0, 0, 0],
                          outputVariableType=kind, storeInternal=True))
        for e in (mid - 1, mid)
        for kind in (exu.OutputVariableType.ForceLocal, exu.OutputVariableType.TorqueLocal)
    ]
    mbs.Assemble()

    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = int(round(args.stop / args.step))
    settings.timeIntegration.endTime = args.stop
    settings.timeIntegration.generalizedAlpha.spectralRadius = args.rho_inf
    settings.timeIntegration.adaptiveStep = False
    settings.timeIntegration.newton.relativeTolerance = args.newton_tol
    settings.timeIntegration.newton.absoluteTolerance = args.newton_abs
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.verboseMode = 0
    settings.solutionSettings.writeSolutionToFile = False  # noqa
    settings.solutionSettings.sensorsWritePeriod = args.sample
    settings.displayStatistics = False
    start = time.time()
    exu.SolveDynamic(mbs, settings)
    elapsed = time.time() - start

    def data(s):
        return mbs.GetSensorStoredData(s)

    pb, pm, pc = (data(s) for s in s_pos)
    times = pb[:, 0]
    fbx, fby = data(s_pin[0]), data(s_pin[1])
    fj = data(s_joint)
    sec = [data(s) for s in s_sec]
    s_half = 0.5 * length
    a_mid = interp(table, "area", s_half)
    i_mid = interp(table, "area_moment", s_half)
    c_mid = interp(table, "fibre_distance", s_half)
    rows = []
    for k, t in enumerate(times):
        b, m, c = pb[k, 1:3], pm[k, 1:3], pc[k, 1:3]
        chord, d = c - b, m - b
        v = (chord[0] * d[1] - chord[1] * d[0]) / math.hypot(*chord)
        axial = 0.5 * (sec[0][k, 1] + sec[2][k, 1])
        moment = 0.5 * (sec[1][k, 3] + sec[3][k, 3])
        stress = abs(axial) / a_mid + abs(moment) * c_mid / i_mid
        # Signs: the constraint force of Exudyn's coordinate constraint is the force on the
        # node's coordinate with a minus sign, so the rod's force on the pin is +lambda; the
        # revolute joint's force acts on its second marker (the slider) with a minus sign.
        rows.append(
            (t, v / length, fbx[k, 1], fby[k, 1], -fj[k, 1], -fj[k, 2], axial, moment, stress)
        )
    header = (
        "# Automotive rod (scenes/automotive_rod.toml) in the slider-crank: crank ramp 0 -> 628.3 rad/s\n"
        "# over 40 ms from rest, then two revolutions; gas pulse 38 kN at 4 pi + 15 deg (see the script).\n"
        f"# Exudyn {exu.GetVersionString()} ObjectBeamGeometricallyExact2D, {n} elements, generalized-alpha\n"
        f"# (spectral radius {args.rho_inf}), h = {args.step:g} s; {elapsed:.0f} s of CPU.\n"
    )
    if args.euler_bernoulli:
        header += "# Euler-Bernoulli limit: shear stiffness x 1e3 (section rotary inertia kept).\n"
    header += (
        "# Command: python tests/data/automotive_reference.py " + " ".join(sys.argv[1:]) + "\n"
        "t,v_mid_rel,FBx,FBy,FCx,FCy,N_mid,M_mid,stress_mid\n"
    )
    with open(args.out, "w") as f:
        f.write(header)
        for row in rows:
            f.write(
                f"{row[0]:.6e},{row[1]:.9e},"
                + ",".join(f"{x:.7e}" for x in row[2:])
                + "\n"
            )
    print(f"{len(rows)} rows to {args.out} in {elapsed:.1f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
