"""docs/sweeps.md quotes the committed resonance study as the peak analysis prints it.

`python -m flexrod_sweep.peaks docs/sweeps/benchmark_resonance --harmonics 2 3 4 5 6 7` prints
one table row per model and harmonic; every row with a peak must stand in docs/sweeps.md cell
for cell (the page's header names the columns in words, and the segment chain's k = 2 row,
which has no local maximum, is described there in words). When the study is regenerated and a
peak moves, this test names the row to update.
"""

import contextlib
import io
import pathlib

from flexrod_sweep import peaks

ROOT = pathlib.Path(__file__).resolve().parents[2]
STUDY = ROOT / "docs" / "sweeps" / "benchmark_resonance"
PAGE = ROOT / "docs" / "sweeps.md"


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def test_peak_table_of_the_docs_is_the_study_s():
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        peaks.main([str(STUDY), "--harmonics", "2", "3", "4", "5", "6", "7"])
    rows = [
        cells(line)
        for line in printed.getvalue().splitlines()
        if line.startswith("| ffr") or line.startswith("| segments")
    ]
    with_peak = [r for r in rows if r[3] and r[3][0].isdigit()]
    assert len(with_peak) >= 10, printed.getvalue()
    page_rows = [cells(line) for line in PAGE.read_text().splitlines() if line.startswith("| ")]
    missing = [r for r in with_peak if r not in page_rows]
    assert not missing, (
        "docs/sweeps.md does not quote these rows of the peak analysis (rerun "
        "`python -m flexrod_sweep.peaks docs/sweeps/benchmark_resonance --harmonics 2 3 4 5 6 7` "
        "and update the table):\n" + "\n".join(" | ".join(r) for r in missing)
    )
