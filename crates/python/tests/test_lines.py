"""fairspline.lines: a table of offsets faired as one hull, through Python."""

import csv
import pathlib

import numpy as np
import pytest

import fairspline

TABLE = (
    pathlib.Path(__file__).resolve().parents[3]
    / "data"
    / "hull_block_island_boat"
    / "offsets_table_inches.csv"
)


def test_lines_fairs_the_block_island_table():
    report, values = fairspline.lines(TABLE)
    offsets = report["offsets"]
    assert values.shape == (len(offsets), 3)
    # The array holds the report's faired coordinates (NaN where the report has none).
    for o, v in zip(offsets, values):
        for k in range(3):
            if o["new"][k] is None:
                assert np.isnan(v[k])
            else:
                assert v[k] == o["new"][k]
    # One faired offset per offset of the table: as many as the table has data rows.
    with open(TABLE, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    assert len(rows) > len(offsets) // 2 and len(rows[0]) == 5
    # Every flagged offset is one the hull would move by more than three steps.
    flagged = [o for o in offsets if o["flagged"]]
    assert len(flagged) == report["flagged"]
    assert all(o["move_steps"] > 3 for o in flagged)
    # The views agree better after than before.
    assert report["consistency_after"]["rms"] < report["consistency_before"]["rms"]


def test_lines_names_the_file_and_line_of_a_bad_value(tmp_path):
    text = TABLE.read_text().splitlines()
    cells = text[4].split(",")
    text[4] = ",".join(cells[:-1] + ["abc"])
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(text) + "\n")
    with pytest.raises(ValueError, match=rf"{bad.name}:5: "):
        fairspline.lines(bad)


def test_lines_refuses_a_bad_setting():
    with pytest.raises(ValueError, match="step"):
        fairspline.lines(TABLE, step=-1.0)
