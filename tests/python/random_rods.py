"""Run the default FMU on the random rods of tests/data/random_rods/ (only physical parameters
set) and compare with the Exudyn reference: the helpers of test_random_rods.py.

What is compared, per start type:
- smooth start (crank ramp over one revolution of the final speed, then two revolutions at it):
  `rod.deflection_rel` pointwise, relative to the reference's peak |v_mid / L|, and each pin's
  force vector pointwise, relative to the peak magnitude of that pin's reference force;
- abrupt start (the crank at full speed from t = 0, the rod undeformed): the forced motion
  plus an undamped free vibration, whose phase after many cycles measures nothing physical.
  The forced motion is v_mid's crank harmonics below two thirds of the dominant ringing
  frequency (fitted by least squares over the run), compared pointwise relative to the overall
  peak of v_mid; the free vibration is v_mid less the forced motion, compared by its spectrum
  (Hann window, zero-padded 16 times, log-parabolic interpolation of frequency and height):
  every local maximum above twice the crank frequency and above 5e-4 of v_mid's peak, in the
  reference's spectrum or in the run's, is paired with the other's nearest one within half the
  crank frequency (over two revolutions the window resolves no closer peaks), and the pair's
  frequency (relative error) and height (error relative to v_mid's peak) are compared; a peak
  without a partner is compared with the other's height at its frequency, and counts as a
  frequency error of 1 unless that height is at least half its own (a shoulder: two peaks the
  window does not resolve in one spectrum). The peaks are the modes' ringing and the
  sidebands the crank's turning puts beside them (the frame's rotation modulates the modes'
  stiffness). A crank harmonic within a third of the ringing frequency of it falls into the
  free vibration and is compared there by its height. The peak |v_mid / L| of every half
  revolution of the whole motion is compared too; it depends on the phases of the peaks
  against each other and against the forced motion, so it measures phase as well as amplitude.
  The reference's pin forces after an abrupt start do not converge pointwise (axial wave
  fronts, see rods.csv conv_f), so they are not compared there.
"""

import csv
import math
from dataclasses import dataclass

import numpy as np
from helpers import ROOT, Slave

DATA = ROOT / "tests" / "data" / "random_rods"

PARAMETERS = {
    "crank.length": "crank_length",
    "rod.length": "rod_length",
    "rod.youngs_modulus": "youngs_modulus",
    "rod.density": "density",
    "rod.area": "area",
    "rod.area_moment": "area_moment",
    "slider.mass": "slider_mass",
    "rod.big_end.mass": "big_end_mass",
    "rod.big_end.inertia": "big_end_inertia",
    "rod.small_end.mass": "small_end_mass",
    "rod.small_end.inertia": "small_end_inertia",
}


def rods():
    """The rows of rods.csv as dicts (numbers as float)."""
    with open(DATA / "rods.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    out = []
    for r in rows:
        out.append({k: (v if k in ("start", "material") else float(v)) for k, v in r.items()})
    return out


def reference(rod_id):
    """t, v_mid_rel, FBx, FBy, FCx, FCy of the reference, as columns."""
    with open(DATA / f"rod_{int(rod_id):02d}.csv") as f:
        lines = [line for line in f if not line.startswith("#")]
    assert lines[0].strip() == "t,v_mid_rel,FBx,FBy,FCx,FCy", lines[0]
    return np.loadtxt(lines[1:], delimiter=",").T


def drive(rod, t, start_angle=0.0):
    """Crank angle, speed and acceleration at t: the ramp omega = W (1 - cos(pi t / T)) / 2 for
    t < T (smooth), then W; constant W from 0 (abrupt), the crank at `start_angle` (rad) then."""
    w = rod["W"]
    if rod["start"] == "abrupt":
        return start_angle + w * t, w, 0.0
    big_t = rod["t_ramp"]
    if t < big_t:
        x = math.pi * t / big_t
        return (
            0.5 * w * (t - big_t / math.pi * math.sin(x)),
            0.5 * w * (1.0 - math.cos(x)),
            0.5 * w * math.pi / big_t * math.sin(x),
        )
    return 0.5 * w * big_t + w * (t - big_t), w, 0.0


@dataclass
class Run:
    t: np.ndarray
    v: np.ndarray
    pins: np.ndarray  # (n, 4): FBx, FBy, FCx, FCy
    estimate: float
    log: list


def simulate(unzipdir, rod, extra=None, start_angle=0.0):
    """The FMU with only the physical parameters of `rod` set, driven at its communication
    step with the crank acceleration as input derivative (an abrupt start at `start_angle`);
    outputs at every second point."""
    slave = Slave(unzipdir, name="rod", logging_on=True)
    vr, s = slave.vr, slave.fmu
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    names = list(PARAMETERS)
    s.setReal([vr[n] for n in names], [rod[PARAMETERS[n]] for n in names])
    for name, value in (extra or {}).items():
        if isinstance(value, int):
            s.setInteger([vr[name]], [value])
        else:
            s.setReal([vr[name]], [value])
    th, om, _ = drive(rod, 0.0, start_angle)
    s.setReal([vr["crank.angle"], vr["crank.speed"]], [th, om])
    # The operating speed, for the rod model `auto` chooses (a smooth start begins at rest).
    s.setReal([vr["crank.design_speed"]], [rod["W"]])
    s.exitInitializationMode()
    dt = rod["dt_comm"]
    n = int(round(rod["t_stop"] / dt))
    outs = [
        vr[k]
        for k in (
            "rod.deflection_rel",
            "pinB.force_x",
            "pinB.force_y",
            "pinC.force_x",
            "pinC.force_y",
            "rod.error_estimate",
        )
    ]
    rows = [(0.0, *s.getReal(outs))]
    for k in range(n):
        t = k * dt
        th, om, al = drive(rod, t, start_angle)
        s.setReal([vr["crank.angle"], vr["crank.speed"]], [th, om])
        s.setRealInputDerivatives([vr["crank.speed"]], [1], [al])
        s.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
        if (k + 1) % 2 == 0:
            rows.append(((k + 1) * dt, *s.getReal(outs)))
    s.terminate()
    s.freeInstance()
    a = np.array(rows)
    return Run(
        t=a[:, 0],
        v=a[:, 1],
        pins=a[:, 2:6],
        estimate=float(a[-1, 6]),
        log=[m for _, _, m in slave.log.messages],
    )


def ringing_frequency(t, v, crank_hz):
    """The frequency of the largest spectral peak of v above 2 x the crank frequency, Hz (local
    maxima only: at the band's lower edge the leakage of the crank harmonics below it can be
    larger than any peak, and is not a ringing)."""
    peaks = spectral_peaks(*spectrum(t, v - v.mean()), 2.0 * crank_hz, 1.0)
    if not peaks:
        raise ValueError(f"no spectral peak of v above 2 x the crank frequency ({crank_hz:.1f} Hz)")
    return peaks[0][0]


def forced(t, v, w, ringing_hz):
    """v's crank harmonics below two thirds of the ringing frequency (fitted by least squares
    over the run): the forced motion. v less it is the free vibration."""
    kmax = int((ringing_hz / 1.5) / (w / (2 * math.pi)))
    cols = [np.ones_like(t)]
    for k in range(1, kmax + 1):
        cols += [np.cos(k * w * t), np.sin(k * w * t)]
    basis = np.stack(cols, axis=1)
    coefficients, *_ = np.linalg.lstsq(basis, v, rcond=None)
    return basis @ coefficients


def spectrum(t, x):
    """x's amplitude spectrum: frequencies (Hz) and heights (Hann window, zero-padded 16 times,
    scaled so that a sinusoid of amplitude a gives a)."""
    window = np.hanning(len(x))
    pad = 16 * len(x)
    return (
        np.fft.rfftfreq(pad, t[1] - t[0]),
        np.abs(np.fft.rfft(x * window, pad)) * 2.0 / window.sum(),
    )


def spectral_peaks(f, spec, f_min, share):
    """(frequency Hz, amplitude) of every local maximum of the spectrum (f, spec) above f_min
    Hz whose height is at least `share` of the largest there (log-parabolic interpolation)."""
    inner = np.flatnonzero(f > f_min)[1:-1]
    maxima = inner[(spec[inner] > spec[inner - 1]) & (spec[inner] >= spec[inner + 1])]
    if len(maxima) == 0:
        return []
    top = spec[maxima].max()
    out = []
    for i in maxima[spec[maxima] >= share * top]:
        a, b, c = np.log(spec[i - 1 : i + 2])
        shift = 0.5 * (a - c) / (a - 2 * b + c)
        out.append((f[i] + shift * (f[1] - f[0]), math.exp(b - 0.25 * (a - c) * shift)))
    return out


def free_vibration_peaks(t, v_run, v_ref, w, ringing_hz, peak):
    """The free vibrations of run and reference by their spectra: every spectral peak of
    either above 2 x the crank frequency and 5e-4 x `peak`, paired with the other's nearest
    within half the crank frequency: (frequency Hz, height / peak, relative frequency error,
    height error / peak), the frequency and height the reference's where it has the peak. A
    peak without a partner where the other spectrum has a shoulder (no local maximum, but at
    least half the height at that frequency: two peaks closer than the window resolves in one)
    is compared with the other's height there and has no frequency error; one without a partner
    and without a shoulder counts with a frequency error of 1."""
    crank_hz = w / (2 * math.pi)
    f_min = 2.0 * crank_hz
    floor = 5e-4 * peak
    ref_spectrum = spectrum(t, v_ref - forced(t, v_ref, w, ringing_hz))
    run_spectrum = spectrum(t, v_run - forced(t, v_run, w, ringing_hz))
    ref_peaks = spectral_peaks(*ref_spectrum, f_min, 0.0)
    run_peaks = spectral_peaks(*run_spectrum, f_min, 0.0)

    def height_at(spectrum_, f):
        return float(np.interp(f, *spectrum_))

    def partner(f, peaks):
        near = [p for p in peaks if abs(p[0] - f) <= 0.5 * crank_hz]
        return min(near, key=lambda p: abs(p[0] - f)) if near else None

    out = []
    for f, a in ref_peaks:
        if a < floor:
            continue
        other = partner(f, run_peaks)
        if other is None:
            h = height_at(run_spectrum, f)
            out.append((f, a / peak, 0.0 if h >= 0.5 * a else 1.0, abs(h - a) / peak))
        else:
            out.append((f, a / peak, abs(other[0] / f - 1.0), abs(other[1] - a) / peak))
    for f, a in run_peaks:
        if a >= floor and partner(f, ref_peaks) is None:
            h = height_at(ref_spectrum, f)
            out.append((f, h / peak, 0.0 if h >= 0.5 * a else 1.0, abs(a - h) / peak))
    return sorted(out)


def half_revolution_peaks(t, v, w):
    """The peak |v| in every whole half revolution of the crank from t = 0, as an array (t on
    the communication grid; a point on a boundary counts to the later half)."""
    k = np.floor(t * w / math.pi + 1e-9).astype(int)
    whole = int(math.floor(t[-1] * w / math.pi + 1e-9))
    return np.array([np.abs(v[k == j]).max() for j in range(whole)])


def compare(rod, run, ref):
    """The measured errors: {"v": ..., "pin_b": ..., "pin_c": ...} (smooth) or {"forced": ...,
    "ringing": ..., "frequency": ..., "amplitude": ..., "peaks": ...} (abrupt; "ringing" and
    "frequency" the largest height and frequency errors over the free vibration's spectral
    peaks, "amplitude" the whole motion's half-revolution peaks), all relative; "measured" the
    error rod.error_estimate is compared with (smooth: v; abrupt: the larger of the forced
    motion's error and the free vibration's height errors)."""
    t, v = ref[0], ref[1]
    assert len(t) == len(run.t) and np.allclose(t, run.t, rtol=0, atol=1e-9 * t[-1])
    peak = np.abs(v).max()
    if rod["start"] == "smooth":
        out = {"v": np.abs(run.v - v).max() / peak}
        for name, cols in (("pin_b", (2, 3)), ("pin_c", (4, 5))):
            f_ref = np.stack([ref[c] for c in cols], axis=1)
            f_run = run.pins[:, [c - 2 for c in cols]]
            scale = np.hypot(f_ref[:, 0], f_ref[:, 1]).max()
            out[name] = np.abs(f_run - f_ref).max() / scale if scale > 0 else 0.0
        out["measured"] = out["v"]
        return out
    w = rod["W"]
    amp_run = half_revolution_peaks(t, run.v, w)
    amp_ref = half_revolution_peaks(t, v, w)
    f_ref = ringing_frequency(t, v, w / (2 * math.pi))
    peaks = free_vibration_peaks(t, run.v, v, w, f_ref, peak)
    out = {
        "forced": np.abs(forced(t, run.v, w, f_ref) - forced(t, v, w, f_ref)).max() / peak,
        "ringing": max(p[3] for p in peaks),
        "frequency": max(p[2] for p in peaks),
        "amplitude": np.abs(amp_run - amp_ref).max() / peak,
        "ringing_hz": f_ref,
        "peaks": peaks,
    }
    out["measured"] = max(out["forced"], out["ringing"])
    return out
