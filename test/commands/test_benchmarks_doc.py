"""docs/benchmarks.md is made from bench/results.json by tools/benchmarks_doc.py, never by hand: the committed page
is the script's output, and a figure the JSON changes is the figure the page shows."""
import importlib.util
import json
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def script():
    spec = importlib.util.spec_from_file_location("benchmarks_doc", REPO / "tools" / "benchmarks_doc.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_committed_page_is_the_script_s_output():
    doc = script()
    assert (REPO / "docs" / "benchmarks.md").read_text() == doc.render(json.loads(doc.RESULTS.read_text())), \
        "docs/benchmarks.md differs from bench/results.json: run python tools/benchmarks_doc.py"


def test_a_figure_of_the_json_is_the_figure_of_the_page():
    doc = script()
    results = json.loads(doc.RESULTS.read_text())
    results["fleet"]["drives_realtime"] = 23
    results["bags"]["analyze_vs_rosbags_read"] = 1.23456
    page = doc.render(results)
    assert "| fleet: 50 kHz drives one 2-core machine monitors in real time | 23 |" in page
    assert "| `analyze_vs_rosbags_read` | 1.235 |" in page
    for bench in results:                     # every bench has its section
        assert f"\n## {bench}\n" in page


def test_check_mode_says_when_the_page_is_stale(tmp_path):
    doc = script()
    stale = tmp_path / "benchmarks.md"
    stale.write_text("# typed by hand\n")
    assert doc.main(["--check", "-o", str(stale)]) == 1
    assert doc.main(["-o", str(stale)]) == 0 and doc.main(["--check", "-o", str(stale)]) == 0
