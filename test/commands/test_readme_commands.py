"""Every command the README shows is run here, as the README writes it: the README's ```bash blocks are read from
the file and run block by block (continuation lines joined), so a README that drifts from the code fails.

`make run` runs as written (the set-up is a no-op when done, then the 10 s real-time pipeline). `make test` is the
one command not run in full -- it is this suite --: its recipe is expanded (`make -n test`) and must call pytest.
DDS stays on loopback, on a domain of the test's own (conftest's ros_env)."""
import json
import re
import subprocess
from pathlib import Path

import pytest
import yaml

from backlash_monitor.workbench.history import HEADER, NOT_CHECKED, version_rows
from backlash_monitor.workbench.measurement import load_measurement
from backlash_monitor.workbench.width import continuous_widths

REPO = Path(__file__).resolve().parents[2]
README = REPO / "README.md"


def bash_blocks() -> list[list[str]]:
    """The README's ```bash blocks, each a list of commands (a line ending in a backslash joined to the next)."""
    blocks = re.findall(r"```bash\n(.*?)```", README.read_text(), flags=re.S)
    out = []
    for block in blocks:
        text = block.replace("\\\n", " ")
        out.append([line.strip() for line in text.splitlines() if line.strip() and not line.strip().startswith("#")])
    return out


def block_with(word: str) -> list[str]:
    [block] = [b for b in bash_blocks() if any(word in c for c in b)]
    return block


def run_bash(commands, cwd, env, timeout):
    script = "set -eo pipefail\n" + "\n".join(c.replace("source env.sh", f"source {REPO}/env.sh") for c in commands)
    return subprocess.run(["bash", "-c", script], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)


def test_the_readme_is_short_and_every_command_of_it_is_run_here():
    assert len(README.read_text().splitlines()) <= 150
    commands = [c for b in bash_blocks() for c in b]
    covered = set(block_with("make run")) | set(block_with("--help")) | set(block_with("diagnose"))
    assert commands and set(commands) == covered, "a README command no test here runs"
    assert all(c.startswith(("make ", "source env.sh", "python -m backlash_monitor ")) for c in commands)


def test_make_test_is_the_suite():
    assert [c.split("#")[0].strip() for c in block_with("make test")] == ["make run", "make test"]
    proc = subprocess.run(["make", "-n", "test"], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0 and "pytest" in proc.stdout


def test_the_shell_block(ros_env):
    proc = run_bash(block_with("--help"), REPO, ros_env, timeout=300)
    assert proc.returncode == 0, proc.stderr
    for command in ("pipeline", "diagnose", "add-effect", "analyze", "bag-info"):
        assert f"    {command} " in proc.stdout


@pytest.mark.slow
@pytest.mark.process
@pytest.mark.ros
def test_make_run_prints_what_the_readme_says(ros_env):
    proc = run_bash(["make run"], REPO, ros_env, timeout=900)
    assert proc.returncode == 0, proc.stderr[-2000:]
    out = proc.stdout
    assert "pipeline: drive, true width 5 mm" in out and "summary: true width 5.00 mm" in out
    # the README's table: every signal's fused width is the simulated drive's 5 mm
    rows = {line.split()[0]: line.split() for line in out.splitlines()
            if line.split() and line.split()[0] in ("a1", "a2", "a1+a2")}
    assert set(rows) == {"a1", "a2", "a1+a2"}
    assert all(r[5] == "5.00" and r[-1] == "yes" for r in rows.values()), rows


@pytest.mark.slow
@pytest.mark.process
def test_the_workbench_loop_finds_the_hidden_friction(tmp_path, ros_env):
    """The loop as the README writes it, on a drive with a dry wheel friction the model lacks: the friction named
    with its torque, the next version written, compared, trained, the width bias gone, and `history` showing it."""
    proc = run_bash(block_with("diagnose"), tmp_path, ros_env, timeout=3000)
    assert proc.returncode == 0, proc.stderr[-3000:]
    diagnosis = json.loads((tmp_path / "diag.json").read_text())
    assert diagnosis["verdict"] in ("discovery", "partial")
    named = {diagnosis["ranked"][0]["effect"], *(a["candidate"] for a in diagnosis["additions"])}
    twins = json.dumps(diagnosis)
    # the friction, or a twin the recording cannot tell from it with the friction flagged beside it
    assert "wheel_coulomb_friction" in named or "wheel_coulomb_friction" in twins
    assert (tmp_path / "report" / "index.html").is_file()
    model = yaml.safe_load((tmp_path / "drive_v2.yaml").read_text())
    assert model["effects_added"], "add-effect wrote no effect into the next version"
    assert (tmp_path / "cmp_v2" / "compare.json").is_file()
    assert (tmp_path / "lib_v2.npz").is_file() and (tmp_path / "lib_v2.watch.npz").is_file()
    assert (tmp_path / "after.csv").is_file()
    # ... and `history` lists v1 (the default model, checked by diagnose) and v2 (checked by compare, trained,
    # analysed) with every cell filled, the residual falling from v1 to v2, and draws it
    rows = version_rows([json.loads(x) for x in (tmp_path / "workbench_history.jsonl").read_text().splitlines()])
    assert [r.version for r in rows] == [1, 2]
    for r in rows:
        cells = dict(zip(HEADER, r.cells()))
        assert all(c.strip() for c in cells.values()), cells
        assert NOT_CHECKED not in cells.values() and cells["monitor width mm"] != "not trained", cells
        assert f"{r.name} v{r.version}" in proc.stdout, proc.stdout[-3000:]
    v1, v2 = rows
    assert max(v2.residual_over_noise_floor.values()) < max(v1.residual_over_noise_floor.values())
    assert dict(zip(HEADER, v2.cells()))["from diagnosis"].startswith("diag.json of ")
    assert (tmp_path / "history.png").stat().st_size > 1000
    # the friction biases the packaged library's width (measured ~0.6 mm); fitted within 20 % of its 1.5 N*m,
    # it is gone with the library trained on v2: |mean continuous width - 7.5 mm| < 0.25 mm, from > 2x that
    fit = next(r for r in diagnosis["ranked"] if r["effect"] == "wheel_coulomb_friction")
    assert abs(fit["parameters"]["torque_Nm"] - 1.5) / 1.5 < 0.20, fit
    (rec,) = (tmp_path / "rec").glob("*.mcap")
    meas = load_measurement(rec)
    before = continuous_widths(meas).mean() * 1e3 - 7.5
    after = continuous_widths(meas, tmp_path / "lib_v2.npz").mean() * 1e3 - 7.5
    assert abs(before) > 2 * 0.25 and abs(after) < 0.25, (before, after)
    # the README quotes diagnose's console: its verdict line is the one this run printed
    readme = README.read_text()
    verdict = next(line for line in proc.stdout.splitlines() if line.startswith("verdict: "))
    assert verdict.split(":")[1].strip() in readme
