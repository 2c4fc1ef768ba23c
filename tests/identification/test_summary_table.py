"""The summary's before/after table at 100 columns, and the diagnosis' warnings said once (realfit35: a TNCscope
trace's time-periodic load made a 130-character row label and a 190-column table; each diagnosis warning was logged
on stderr and printed again under the table)."""

from __future__ import annotations

import logging
from html import escape

from identification.diagnosis import TABLE_COLUMNS, after_table_lines, before_after_rows, format_before_after
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X
from vcnc.cli import main

#: The effect summary of the TNCscope trace tnc_N300 (FeedStep150_N300_H55.sco, Duncan-McPherson/Thesis-Work).
LONG = ("period 0.018183 s, 1 harmonics, peak-to-peak 2743 mm/s^2, on 9.666..13.62 s, amplitude 1372 -> 1372 "
        "mm/s^2")


def _diagnosed() -> ReducedAxisModel:
    effect = {"name": "time_periodic", "summary": LONG, "parameters": {}, "rms_before_um": 2.108,
              "rms_after_um": 0.653, "validation_rms_before_um": 2.120, "validation_rms_after_um": 0.679}
    validation = {"record_rms_um": [1.352, 0.419], "identification_rms_before_um": 2.108, "rms_before_um": 2.120,
                  "warning": "reduced-model poles on the bounds (zeta = 2 at its upper bound)"}
    return ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=0.003, axis="y", effects=[effect],
                            validation=validation)


def test_the_table_keeps_to_100_columns_and_says_what_each_effect_fitted_below_it():
    text = format_before_after(_diagnosed())
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= TABLE_COLUMNS == 100
    assert lines[3].startswith("+ time_periodic  ") and "1.352" in lines[2] and "0.419" in lines[3]
    assert lines[4].startswith("final model  ") and "0.419" in lines[4]
    assert text.count("+ time_periodic") == 2 and text.count("period 0.018183 s") == 1  # its row, its description
    described = " ".join(line.strip() for line in lines if "period 0.018183" in line or line.startswith("    "))
    assert described.startswith("+ time_periodic: period 0.018183 s") and described.endswith("1372 -> 1372 mm/s^2")
    assert text.count("reduced-model poles on the bounds") == 1


def test_the_lines_after_the_table_are_the_summarys_own_whatever_the_table_holds():
    """The HTML report prints the summary's lines after its table from ``after_table_lines``, not by counting the
    table's lines (review35: the report sliced the text at ``2 + len(rows)``, which a wrapped description or a
    changed layout would have shifted)."""
    model = _diagnosed()
    lines = format_before_after(model).splitlines()
    after = after_table_lines(model)
    assert lines[2 + len(before_after_rows(model)):] == "\n".join(after).splitlines()
    assert after[0].startswith("+ time_periodic: period 0.018183 s")  # a wrapped paragraph is one entry
    assert "\n" in after[0] and any(line == "warning: reduced-model poles on the bounds (zeta = 2 at its upper bound)"
                                    for line in after)


def test_a_diagnosis_warning_is_not_also_logged(tmp_path, capsys, caplog):
    """A one-way record's summary (test_one_way.py's loop and record, 4600 samples): its folds' missing direction is
    said once, with the fold list (it was said for each fold, and again for each fold's training folds: four
    warnings), and every line keeps to 100 columns, as the table (the sample note, the split and the naive
    predictions ran to 275, 282 and 321 columns; coulombjoint36); the HTML report says the same words, unwrapped."""
    from tests.identification.test_one_way import _one_way

    path = tmp_path / "one_way.csv"
    _one_way(1.0).to_csv(path)
    with caplog.at_level(logging.WARNING):
        assert main(["identify", str(path), "--report", str(tmp_path / "report")]) == 0
    out = capsys.readouterr().out
    assert not [r for r in caplog.records if r.name.startswith("identification.diagnosis")]
    lines = out.splitlines()
    assert max(len(line) for line in lines) <= TABLE_COLUMNS
    assert out.count("no negative motion") == 1 and "the folds other than" not in out
    said_so = (
        ["warning: validation folds 1, 2 (samples 0..3565, 3565..4600) have no negative motion:",
         "    direction-dependent effects are not validated there"],
        ["samples: 'all' the record's 4600; 'ident' and 'valid' its 4600 active ones (idle stretches, where an",
         "    axis at rest is predicted for free, trimmed with a 0.2 s margin), 'valid' each fold's predicted",
         "    by the model refitted on the others; all simulated on the record's sample grid"],
        ["validation: 2 contiguous folds cut where the reference stands still or reverses; each is held out in",
         "    turn (the fit on all active samples refitted on the other folds by up to 5 Levenberg-Marquardt",
         "    iterations) and the held-out errors pooled; idle stretches trimmed with a 0.2 s margin"])
    for said in said_so:
        i = lines.index(said[0])
        assert lines[i:i + len(said)] == said
    naive = lines.index("naive predictions of the capture: the commanded position itself rms 418.3 um (the "
                        "following error),")
    assert lines[naive + 1].startswith("    delayed by 3 samples (0.003 s) rms 351.3 um; the model predicts ")
    assert "friction: the record moves in the positive direction only: the Coulomb level of the negative" in out
    # the report's paragraphs are the summary's lines, unwrapped: the same words
    html = (tmp_path / "report" / "index.html").read_text()
    paragraphs = []
    for line in lines:
        if line.startswith("    ") and paragraphs:
            paragraphs[-1] += " " + line.strip()
        else:
            paragraphs.append(line)
    for p in paragraphs:
        if p.startswith(("samples:", "validation:", "warning:", "naive predictions", "residual:", "reference dead")):
            assert f"<p>{escape(p)}</p>" in html, p
