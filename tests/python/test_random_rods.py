"""The default FMU on 44 random rods with only physical parameters and the operating speed set, against Exudyn's
geometrically exact shear beam (tests/data/random_rods/, written by
tests/data/random_rods_reference.py; what is compared: random_rods.py).

Asserted, with the targets the numbers are measured against:
- smooth starts: each pin's force within 1 % of its peak pointwise; v_mid / L within 0.5 % of
  its peak pointwise, or else the FMU warned that rod.error_estimate passed solver.tolerance;
  rod.error_estimate within a factor 3 of the measured error;
- abrupt starts: the forced motion within 0.5 % of the peak pointwise, every spectral peak of
  the free vibration within 0.5 % in frequency and within 0.5 % of the peak in height, the
  whole motion's half-revolution peaks (which depend on the phases too) within 2 %;
  rod.error_estimate within a factor 3 of the larger of the forced motion's and the peaks'
  height errors (docs/verification.md, "Any rod", lists each rod).
The table of every rod is docs/generated/random-rods.md (FLEXROD_BLESS=1 rewrites it).
"""

import math
import os

import numpy as np
import pytest
import random_rods as rr
from helpers import ROOT

FRAGMENT = ROOT / "docs" / "generated" / "random-rods.md"
RESOLUTION_FRAGMENT = ROOT / "docs" / "generated" / "random-rods-resolution.md"


def pct(x):
    return f"{100 * x:.2f} %"


@pytest.fixture(scope="module")
def results(default_unzipdir):
    out = []
    for rod in rr.rods():
        run = rr.simulate(default_unzipdir, rod)
        out.append((rod, run, rr.compare(rod, run, rr.reference(rod["id"]))))
    return out


def table(results):
    smooth = [(r, run, m) for r, run, m in results if r["start"] == "smooth"]
    abrupt = [(r, run, m) for r, run, m in results if r["start"] == "abrupt"]
    within = sum(m["v"] <= 0.005 for _, _, m in smooth)
    ratios = [run.estimate / m["measured"] for _, run, m in smooth]
    amp_within = sum(m["amplitude"] <= 0.005 for _, _, m in abrupt)
    forced_within = sum(m["forced"] <= 0.005 for _, _, m in abrupt)
    ring_within = sum(m["ringing"] <= 0.005 for _, _, m in abrupt)
    abrupt_ratios = [run.estimate / m["measured"] for _, run, m in abrupt]
    freq_within = sum(m["frequency"] <= 0.005 for _, _, m in abrupt)
    peaks = [len(m["peaks"]) for _, _, m in abrupt]
    lines = [
        "<!-- written by `FLEXROD_BLESS=1 .venv/bin/python -m pytest tests/python/test_random_rods.py` (after `cargo run --release -p fmu`): rerun it, do not edit -->",
        f"{len(results)} rods (slenderness {min(r['slenderness'] for r, _, _ in results):.1f} to "
        f"{max(r['slenderness'] for r, _, _ in results):.1f}, slider 0 to "
        f"{max(r['slider_mass'] / r['rod_mass'] for r, _, _ in results):.2f} times the rod's mass, "
        f"end bodies on {sum(r['big_end_mass'] > 0 for r, _, _ in results)}, peak v_mid/L "
        f"{min(r['peak_v_rel'] for r, _, _ in results):.4f} to {max(r['peak_v_rel'] for r, _, _ in results):.4f}), "
        "the default FMU with only physical parameters and the operating speed (`crank.design_speed`) set:",
        "",
        f"- {len(smooth)} smooth starts: v_mid/L within 0.5 % of its peak pointwise on {within}; largest "
        f"{pct(max(m['v'] for _, _, m in smooth))}. Pin forces within "
        f"{pct(max(max(m['pin_b'], m['pin_c']) for _, _, m in smooth))} of their peaks. "
        f"rod.error_estimate / measured error {min(ratios):.2f} to {max(ratios):.2f}.",
        f"- {len(abrupt)} abrupt starts: forced motion within 0.5 % of the peak pointwise on "
        f"{forced_within} (largest {pct(max(m['forced'] for _, _, m in abrupt))}); the free "
        f"vibration's {min(peaks)} to {max(peaks)} spectral peaks within 0.5 % in frequency on "
        f"{freq_within} (largest {pct(max(m['frequency'] for _, _, m in abrupt))}) and within "
        f"0.5 % of the peak in height on {ring_within} (largest "
        f"{pct(max(m['ringing'] for _, _, m in abrupt))}); half-revolution peaks of the whole "
        f"motion within 0.5 % on {amp_within} (largest "
        f"{pct(max(m['amplitude'] for _, _, m in abrupt))}). rod.error_estimate / the larger of "
        f"the forced motion's and the peaks' height errors {min(abrupt_ratios):.2f} to "
        f"{max(abrupt_ratios):.2f}.",
        "",
        "| rod | start | L/h | slider / rod mass | peak v_mid/L | v_mid error, or forced motion, free vibration's heights (whole motion's half-revolution peaks) | pin B, pin C or free vibration's frequencies | rod.error_estimate |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for rod, run, m in results:
        if rod["start"] == "smooth":
            first, second = pct(m["v"]), f"{pct(m['pin_b'])}, {pct(m['pin_c'])}"
        else:
            first = f"{pct(m['forced'])}, {pct(m['ringing'])} ({pct(m['amplitude'])})"
            second = pct(m["frequency"])
        lines.append(
            f"| {int(rod['id'])} | {rod['start']} | {rod['slenderness']:.1f} | "
            f"{rod['slider_mass'] / rod['rod_mass']:.2f} | {rod['peak_v_rel']:.4f} | {first} | "
            f"{second} | {pct(run.estimate)} |"
        )
    return "\n".join(lines) + "\n"


def test_smooth_starts(results):
    failures = []
    for rod, run, m in results:
        if rod["start"] != "smooth":
            continue
        warned = any(msg.startswith("rod.error_estimate") for msg in run.log)
        if not (m["v"] <= 0.005 or warned):
            failures.append(f"rod {rod['id']:.0f}: v {m['v']:.2e} without a warning")
        if max(m["pin_b"], m["pin_c"]) > 0.01:
            failures.append(f"rod {rod['id']:.0f}: pins {m['pin_b']:.2e}, {m['pin_c']:.2e}")
        if not 1 / 3 <= run.estimate / m["measured"] <= 3:
            failures.append(
                f"rod {rod['id']:.0f}: estimate {run.estimate:.2e} against {m['v']:.2e}"
            )
    assert not failures, "\n".join(failures)


def test_abrupt_starts(results):
    failures = []
    for rod, run, m in results:
        if rod["start"] != "abrupt":
            continue
        if max(m["forced"], m["frequency"], m["ringing"]) > 0.005 or m["amplitude"] > 0.02:
            failures.append(f"rod {rod['id']:.0f}: {m}")
        if not 1 / 3 <= run.estimate / m["measured"] <= 3:
            failures.append(
                f"rod {rod['id']:.0f}: estimate {run.estimate:.2e} against {m['measured']:.2e}"
            )
    assert not failures, "\n".join(failures)


def test_table_of_the_docs_is_current(results):
    text = table(results)
    if os.environ.get("FLEXROD_BLESS"):
        FRAGMENT.write_text(text)
    assert FRAGMENT.read_text() == text, f"{FRAGMENT} is stale; FLEXROD_BLESS=1 rewrites it"


MODAL_FRAGMENT = ROOT / "docs" / "generated" / "random-rods-modal.md"
MODAL = {"rod.model_index": 3, "rod.elements": 48}


@pytest.fixture(scope="module")
def modal_results(default_unzipdir):
    """The same rods with rod.model = modal_segments (48 segments; the bending modes up to 20
    times the first, the slider-rod axial mode where `auto` takes it in)."""
    out = []
    for rod in rr.rods():
        run = rr.simulate(default_unzipdir, rod, MODAL)
        out.append((rod, run, rr.compare(rod, run, rr.reference(rod["id"]))))
    return out


def test_modal_segments_on_the_random_rods(modal_results):
    """The chain on its modes with only the physical parameters and the model set: after smooth
    starts v_mid within 0.5 % of its peak, the pin forces within 1.5 %, and rod.error_estimate
    never below a third of the measured error (above three times it only where it stays below
    the tolerance: the chain's discretization share is conservative on slender rods); after
    abrupt starts the forced motion within 0.5 % pointwise and the free vibration's spectral
    peaks within 0.5 % in frequency and height (what the table of the docs states, rod by rod in
    the test output)."""
    failures = []
    for rod, run, m in modal_results:
        if rod["start"] == "smooth":
            if m["v"] > 0.005 or max(m["pin_b"], m["pin_c"]) > 0.015:
                failures.append(f"rod {rod['id']:.0f}: {m}")
            if not (
                run.estimate >= m["v"] / 3 and (run.estimate <= 3 * m["v"] or run.estimate <= 1e-3)
            ):
                failures.append(
                    f"rod {rod['id']:.0f}: estimate {run.estimate:.2e} against {m['v']:.2e}"
                )
        elif max(m["forced"], m["frequency"], m["ringing"]) > 0.005:
            failures.append(f"rod {rod['id']:.0f}: {m}")
        print(rod["id"], rod["start"], m, run.estimate)
    assert not failures, "\n".join(failures)
    text = modal_table(modal_results)
    if os.environ.get("FLEXROD_BLESS"):
        MODAL_FRAGMENT.write_text(text)
    assert MODAL_FRAGMENT.read_text() == text, (
        f"{MODAL_FRAGMENT} is stale; FLEXROD_BLESS=1 rewrites it"
    )


def modal_table(results):
    smooth = [(r, run, m) for r, run, m in results if r["start"] == "smooth"]
    abrupt = [(r, run, m) for r, run, m in results if r["start"] == "abrupt"]
    ratios = [run.estimate / m["v"] for _, run, m in smooth]
    lines = [
        "<!-- written by `FLEXROD_BLESS=1 .venv/bin/python -m pytest tests/python/test_random_rods.py` (after `cargo run --release -p fmu`): rerun it, do not edit -->",
        f"The same {len(results)} rods with `rod.model_index = 3` (the chain on its modes, `rod.elements = 48`), only the physical parameters set otherwise:",
        "",
        f"- {len(smooth)} smooth starts: v_mid/L within {pct(max(m['v'] for _, _, m in smooth))} of its peak "
        f"pointwise; pin forces within {pct(max(max(m['pin_b'], m['pin_c']) for _, _, m in smooth))}; "
        f"rod.error_estimate / measured error {min(ratios):.2f} to {max(ratios):.2f}.",
        f"- {len(abrupt)} abrupt starts: forced motion within "
        f"{pct(max(m['forced'] for _, _, m in abrupt))} of the peak pointwise; the free vibration's "
        f"spectral peaks within {pct(max(m['frequency'] for _, _, m in abrupt))} in frequency and "
        f"{pct(max(m['ringing'] for _, _, m in abrupt))} of the peak in height.",
    ]
    return "\n".join(lines) + "\n"


# The finer modal resolution of the resolution study: more bending modes on a finer mesh.
FINE = {"rod.modes": 6, "rod.elements": 32}


def higher_peaks(m):
    """The free vibration's spectral peaks above 3 x the dominant ringing frequency and 0.5 % of
    v_mid's peak (a higher bending mode's ringing and its sidebands): (frequency Hz, relative
    frequency error)."""
    return [(f, df) for f, h, df, _ in m["peaks"] if f > 3.0 * m["ringing_hz"] and h >= 0.005]


def test_finer_modes_resolve_the_higher_modes_of_abrupt_starts(default_unzipdir, results):
    """After abrupt starts the free vibration rings in every mode; the default FMU's 3 modes on
    8 elements place the higher bending modes less exactly than the first, and the whole
    motion's half-revolution peaks follow their phases against the rest. On every abrupt start
    that rings in a higher mode (spectral peaks above 3 x its dominant ringing frequency and
    0.5 % of the peak), 6 modes on 32 elements bring each of those peaks within 0.03 % in
    frequency and the whole motion's peaks no further off than with the defaults (the table of
    the docs)."""
    rows, failures = [], []
    for rod, _, m in results:
        if rod["start"] != "abrupt" or not higher_peaks(m):
            continue
        extra = {"crank.design_speed": rod["W"], **FINE}
        fine = rr.compare(rod, rr.simulate(default_unzipdir, rod, extra), rr.reference(rod["id"]))
        rows.append((rod, m, fine))
        frequencies = {f for f, _ in higher_peaks(m)}
        worst = max(df for f, _, df, _ in fine["peaks"] if f in frequencies)
        if not (worst <= 3e-4 and fine["amplitude"] <= m["amplitude"]):
            failures.append(
                f"rod {rod['id']:.0f}: higher modes {worst:.2e}, peaks {m['amplitude']:.2e} -> "
                f"{fine['amplitude']:.2e}"
            )
    assert rows, "no abrupt start rings in a mode above 3 x its dominant one"
    assert not failures, "\n".join(failures)
    lines = [
        "<!-- written by `FLEXROD_BLESS=1 .venv/bin/python -m pytest tests/python/test_random_rods.py` (after `cargo run --release -p fmu`): rerun it, do not edit -->",
        "| rod | L/h | slider / rod mass | higher mode's spectral peaks, Hz | their frequency error, defaults (3 modes, 8 elements) | with `rod.modes = 6`, `rod.elements = 32` | whole motion's half-revolution peaks, defaults | with 6 modes, 32 elements |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for rod, m, fine in rows:
        frequencies = [f for f, _ in higher_peaks(m)]
        fine_errors = [df for f, _, df, _ in fine["peaks"] if f in frequencies]
        lines.append(
            f"| {rod['id']:.0f} | {rod['slenderness']:.1f} | {rod['slider_mass'] / rod['rod_mass']:.2f} | "
            f"{', '.join(f'{f:.0f}' for f in frequencies)} | "
            f"{pct(max(df for _, df in higher_peaks(m)))} | {pct(max(fine_errors))} | "
            f"{pct(m['amplitude'])} | {pct(fine['amplitude'])} |"
        )
    text = "\n".join(lines) + "\n"
    if os.environ.get("FLEXROD_BLESS"):
        RESOLUTION_FRAGMENT.write_text(text)
    assert RESOLUTION_FRAGMENT.read_text() == text, (
        f"{RESOLUTION_FRAGMENT} is stale; FLEXROD_BLESS=1 rewrites it"
    )


START_FRAGMENT = ROOT / "docs" / "generated" / "random-rods-start.md"
# The reference of the starts at a quarter revolution: the chain on its modes, geometrically
# exact, on 64 segments (checked against the exact beam on the abrupt starts at dead centre in
# the same test).
QUARTER_REFERENCE = {"rod.model_index": 3, "rod.elements": 64}


def start_vibration(run):
    """The free vibration of the start the FMU logged, v_mid / L (0 if none was logged)."""
    for message in run.log:
        if "rings a free vibration of about" in message:
            return float(message.split("rings a free vibration of about ")[1].split()[0])
    return 0.0


def ringing_of(t, v, w):
    """A reference's free vibration at its largest: its peak |v| less its forced motion's."""
    forced = rr.forced(t, v, w, rr.ringing_frequency(t, v, w / (2 * math.pi)))
    return np.abs(v).max() - np.abs(forced).max()


def test_abrupt_starts_at_a_quarter_revolution(default_unzipdir, results):
    """The abrupt starts again with the crank at a quarter revolution, where the rod's
    transverse load is largest at the start and the start rings more, against the chain on its
    modes (64 segments; at dead centre within 0.05 % of the exact beam's forced motion and
    free-vibration heights, checked here): the forced motion within 0.5 % pointwise, the free vibration's
    spectral peaks within 0.5 % in frequency and height, rod.error_estimate within a factor 3
    of the larger error; and at both start angles the free vibration the FMU estimates at the
    start (its log) within a factor 2 of the reference's (its peak less its forced motion's)."""
    failures, ratios, forced_share, vibration = [], [], [], {0.0: [], 0.5: []}
    reference_error = []
    for rod, run, _ in results:
        if rod["start"] != "abrupt":
            continue
        w = rod["W"]
        ref = rr.reference(rod["id"])
        vibration[0.0].append(start_vibration(run) / ringing_of(ref[0], ref[1], w))
        extra = {"crank.design_speed": w}
        # The reference itself against the exact beam, at dead centre.
        own = rr.compare(
            rod, rr.simulate(default_unzipdir, rod, {**extra, **QUARTER_REFERENCE}), ref
        )
        reference_error.append(own["measured"])
        if own["measured"] > 5e-4:
            failures.append(f"rod {rod['id']:.0f}: the reference {own}")
        quarter = rr.simulate(default_unzipdir, rod, extra, start_angle=math.pi / 2)
        chain = rr.simulate(
            default_unzipdir, rod, {**extra, **QUARTER_REFERENCE}, start_angle=math.pi / 2
        )
        reference = np.vstack([chain.t, chain.v, chain.pins.T])
        m = rr.compare(rod, quarter, reference)
        ratios.append(quarter.estimate / m["measured"])
        f_ref = rr.ringing_frequency(chain.t, chain.v, w / (2 * math.pi))
        forced_share.append(
            np.abs(rr.forced(chain.t, chain.v, w, f_ref)).max() / np.abs(chain.v).max()
        )
        vibration[0.5].append(start_vibration(quarter) / ringing_of(chain.t, chain.v, w))
        print(
            rod["id"],
            m["forced"],
            m["frequency"],
            m["ringing"],
            quarter.estimate,
            ratios[-1],
            vibration[0.0][-1],
            vibration[0.5][-1],
        )
        if max(m["forced"], m["frequency"], m["ringing"]) > 0.005 or not 1 / 3 <= ratios[-1] <= 3:
            failures.append(f"rod {rod['id']:.0f}: {m}, estimate {quarter.estimate:.2e}")
    for angle, values in vibration.items():
        if not all(0.5 <= x <= 2.0 for x in values):
            failures.append(f"start vibration at {angle} revolutions: {values}")
    assert not failures, "\n".join(failures)
    text = (
        "\n".join(
            [
                "<!-- written by `FLEXROD_BLESS=1 .venv/bin/python -m pytest tests/python/test_random_rods.py` (after `cargo run --release -p fmu`): rerun it, do not edit -->",
                f"- The free vibration a start at speed rings, as the FMU estimates it at the start "
                f"(logged; quasi-static): {min(vibration[0.0]):.2f} to {max(vibration[0.0]):.2f} times the "
                f"reference's (its peak less its forced motion's) at dead centre, {min(vibration[0.5]):.2f} "
                f"to {max(vibration[0.5]):.2f} times the chain's at a quarter revolution.",
                f"- The {len(ratios)} abrupt starts from a quarter revolution against the chain on its modes "
                f"(64 segments; after the starts at dead centre within {pct(max(reference_error))} of the "
                f"exact beam's forced motion and free-vibration heights): forced motion {min(forced_share):.2f} to {max(forced_share):.2f} of the "
                f"peak; rod.error_estimate / the larger of the forced motion's and the free vibration's "
                f"height errors {min(ratios):.2f} to {max(ratios):.2f}.",
            ]
        )
        + "\n"
    )
    if os.environ.get("FLEXROD_BLESS"):
        START_FRAGMENT.write_text(text)
    assert START_FRAGMENT.read_text() == text, (
        f"{START_FRAGMENT} is stale; FLEXROD_BLESS=1 rewrites it"
    )
