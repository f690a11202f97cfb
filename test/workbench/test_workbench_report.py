"""The diagnosis report renders in a real headless browser (Debian's chromium; `make chromium` installs it):
the screenshot is not blank and every <img> loaded (naturalWidth > 0). The page opens with its header (date, tool
version, drive, nominal conditions, units) and the summary, then the figures (the per-event residual among them)
before any table, and links the diagnosis JSON instead of printing it."""
import shutil
import subprocess

import pytest

from backlash_monitor.workbench import report
from backlash_monitor.workbench.diagnose import diagnose
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
MARKER_SCRIPT = """<script>
window.addEventListener('load', function () {
  var imgs = document.images, ok = imgs.length > 0;
  for (var i = 0; i < imgs.length; i++) { if (!(imgs[i].complete && imgs[i].naturalWidth > 0)) ok = false; }
  document.body.setAttribute('data-images', ok ? 'all-loaded:' + imgs.length : 'missing');
});
</script></body>"""


def _chromium(*args, timeout=90):
    return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                           "--virtual-time-budget=5000", *args], capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("report")
    model = load_model(None)
    meas = hidden_effect_recording(model, 2.0, seed=51, config_overrides={
        "effects.load_mass_drift": True, "load_mass_drift.relative_change": 0.3})
    res = diagnose(meas, model, seeds=[0, 1, 2], effects=["load_mass_drift", "wheel_inertia_drift"], propose=False)
    page = report.write_report(res, d)
    return page


def test_report_opens_with_header_summary_and_figures(report_dir):
    import json

    from backlash_monitor import __version__
    html = report_dir.read_text()
    for label in ("date", "tool", "drive (recording)", "model", "nominal conditions", "units"):
        assert f"<th>{label}</th>" in html, label
    assert f"backlash_monitor {__version__}" in html
    assert "backlash width 7.50 mm" in html                      # the model's nominal width, in mm
    assert "m/s²" in html
    summary, first_img, first_table_after_header = (html.index("<h2>Summary</h2>"), html.index("<img "),
                                                    html.index("<table>"))
    assert summary < first_img < first_table_after_header       # summary, then the plots, then the tables
    assert "event_residuals.png" in html
    assert "<pre>" not in html                                   # no raw JSON dump
    assert "href='diagnosis.json'" in html
    data = json.loads((report_dir.parent / "diagnosis.json").read_text())
    assert data["verdict"] in html
    assert "ΔIC:" in html and "T²:" in html                      # the two terms explained


@pytest.mark.process
@pytest.mark.skipif(CHROMIUM is None, reason="chromium missing: run `make chromium` (make test does)")
def test_report_renders_with_all_images(report_dir, tmp_path):
    html = report_dir.read_text()
    n_img = html.count("<img ")
    assert n_img >= 5
    for name in ("event_average.png", "event_residuals.png", "where.png", "ranked.png", "spectra.png"):
        assert (report_dir.parent / name).stat().st_size > 1000
    probe = report_dir.with_name("probe.html")
    probe.write_text(html.replace("</body>", MARKER_SCRIPT))
    dom = _chromium("--dump-dom", probe.as_uri()).stdout
    assert f'data-images="all-loaded:{n_img}"' in dom
    shot = tmp_path / "shot.png"
    _chromium(f"--screenshot={shot}", "--window-size=1200,2000", report_dir.as_uri())
    import matplotlib.image as mpimg
    img = mpimg.imread(shot)
    assert img.shape[0] > 500 and img.shape[1] > 500
    grey = img[..., :3].mean(axis=-1)
    assert grey.std() > 0.05                                  # not a blank page
    assert (grey < 0.5).mean() > 0.005                        # text and plot lines drawn
