"""The main job end to end: ``vcnc demo`` writes a report a person can read.

The demo runs once per session (it is the expensive part); the report is then checked as a file
tree, as JSON, and as a page rendered by headless Chromium (Debian's ``chromium``, installed by
``make test`` / ``.ci/run`` when missing).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

from vcnc import demo

pytestmark = pytest.mark.slow  # runs the demo end to end (minutes)

CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--disable-dev-shm-usage",
]


@pytest.fixture(scope="module")
def demo_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo") / "report"
    summary = demo.run_demo(out, progress=False)
    return out, summary


def test_demo_finds_the_hidden_backlash(demo_run):
    _, summary = demo_run
    hidden = summary["hidden_effect"]
    assert hidden["name"] == "backlash"
    found = summary["axes"][hidden["axis"]]["effects"]
    assert found and found[0]["name"] == "backlash"
    width = found[0]["parameters"]["width_mm"]
    assert width == pytest.approx(hidden["parameters"]["width_mm"], rel=0.2)
    val = summary["axes"][hidden["axis"]]["validation"]
    assert val["rms_after_um"] < val["rms_before_um"] / 2


def test_demo_summary_and_files(demo_run):
    out, summary = demo_run
    on_disk = json.loads((out / "summary.json").read_text())
    assert on_disk["machine"] == "fadal-pid"
    for name in ("index.html", "summary.json", "identification_test.png", "frf_x.png", "model_x.json"):
        assert (out / name).is_file(), name
    assert list(out.glob("contour_*.png")), "contour figures missing"
    assert any(out.glob("*.fmu")), "validated FMU missing"
    rows = {r["toolpath"]: r for r in summary["contours"]}
    assert set(rows) == {"circle", "diamond"}
    for r in rows.values():
        assert r["true_max_um"] > 0
        assert np.isfinite(r["augmented_max_um"])
    model = json.loads((out / "model_x.json").read_text())
    assert model["format"] == "vcnc.axis-model/1"


def _chromium() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    assert path, "Debian's chromium is required (make test installs it: apt-get install chromium)"
    return path


def test_report_renders_in_chromium(demo_run, tmp_path):
    out, _ = demo_run
    page = (out / "index.html").read_text()
    assert "src='data:image/png;base64," in page  # self-contained: images embedded
    # A probe script reports, after load, how many images there are and how many decoded.
    probe = (
        "<script>window.addEventListener('load',()=>{const im=[...document.images];"
        "const ok=im.filter(i=>i.complete&&i.naturalWidth>0).length;"
        "const p=document.createElement('pre');p.id='probe';"
        "p.textContent='IMAGES '+im.length+' LOADED '+ok+' TEXT '+document.body.innerText.length;"
        "document.body.appendChild(p);});</script>"
    )
    probed = tmp_path / "probed.html"
    probed.write_text(page.replace("</body>", probe + "</body>"))
    args = [_chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
            "--virtual-time-budget=5000", "--dump-dom", probed.as_uri()]
    r = subprocess.run(args, capture_output=True, text=True, timeout=120)
    m = re.search(r"IMAGES (\d+) LOADED (\d+) TEXT (\d+)", r.stdout)
    assert m, f"probe did not run; chromium said: {r.stderr[-2000:]}"
    n_images, n_loaded, n_text = map(int, m.groups())
    assert n_images >= 5
    assert n_loaded == n_images
    assert n_text > 500  # not blank: the story and tables are there
    # and a screenshot that is not a blank page
    shot = tmp_path / "shot.png"
    args = [_chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / 'profile2'}",
            f"--screenshot={shot}", "--window-size=1200,2000", (out / "index.html").as_uri()]
    subprocess.run(args, capture_output=True, text=True, timeout=120)
    import matplotlib.image

    img = matplotlib.image.imread(shot)
    assert img.std() > 0.05


def test_cli_demo_missing_emps_is_bad_input(tmp_path):
    r = subprocess.run([sys.executable, "-m", "vcnc", "demo", "--emps", str(tmp_path / "nothing")],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2
    assert r.stderr.startswith("error:")
    assert "nonlinearbenchmark.org" in r.stderr
    assert not (tmp_path / "vcnc-demo-emps").exists()


def test_cli_demo_emps_without_folder_says_none_was_given(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "VCNC_EMPS_DIR"}
    r = subprocess.run([sys.executable, "-m", "vcnc", "demo", "--emps"], capture_output=True, text=True,
                       cwd=tmp_path, env=env)
    assert r.returncode == 2
    assert r.stderr.startswith("error: EMPS data not found (no folder given: --emps without DIR and VCNC_EMPS_DIR "
                               "unset); download DATA_EMPS.mat")
    assert not (tmp_path / "vcnc-demo-emps").exists()
