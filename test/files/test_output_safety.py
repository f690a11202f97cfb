"""No command writes over its input or over an existing recording unless told to (--overwrite);
outputs appear under their final name only once complete."""
import hashlib
import subprocess
import sys

import pytest

from backlash_monitor.bag import BagReader
from backlash_monitor.files.outputs import OutputError, check_outputs, partial_path, staged_outputs


def _digest(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _cli(*args, env=None, timeout=300):
    if args[0] == "analyze":     # (files, not the model fit: ~3.5 s of CPU less a call, test/fleet/test_one_bag_model_fit.py)
        args = (*args, "--no-model-fit")
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)],
                          capture_output=True, text=True, timeout=timeout, env=env)


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """A 1 s bag of one simulated drive, as `simulate --mcap` writes it (RUN.mcap)."""
    directory = tmp_path_factory.mktemp("rec")
    proc = _cli("simulate", "--widths", "0.005", "--eta-k", "0.025", "--n1", "0.89",
                "--duration", "1", "--no-npz", "--mcap", directory, "--no-progress")
    assert proc.returncode == 0, proc.stderr
    bags = sorted(directory.glob("*.mcap"))
    assert len(bags) == 1, bags
    return bags[0]


@pytest.mark.process
def test_analyze_without_out_keeps_the_recording_and_writes_beside_it(recording, tmp_path):
    bag = tmp_path / "run.mcap"
    bag.write_bytes(recording.read_bytes())
    before = _digest(bag)
    proc = _cli("analyze", bag)
    assert proc.returncode == 0, proc.stderr
    assert _digest(bag) == before, "analyze wrote over the recording it analysed"
    for ext in ("csv", "json", "mcap"):
        assert (tmp_path / f"run.estimates.{ext}").is_file()
    with BagReader(tmp_path / "run.estimates.mcap") as reader:
        assert "/estimate" in reader.topics
    with BagReader(bag) as reader:   # the recording still holds its signals
        assert "/plant/a1" in reader.topics
    assert not list(tmp_path.glob("*.partial"))


@pytest.mark.process
def test_analyze_refuses_existing_outputs_unless_overwrite(recording, tmp_path):
    bag = tmp_path / "run.mcap"
    bag.write_bytes(recording.read_bytes())
    assert _cli("analyze", bag).returncode == 0
    csv_path = tmp_path / "run.estimates.csv"
    csv_path.write_text("kept\n")
    proc = _cli("analyze", bag)
    assert proc.returncode == 2
    assert "exists already" in proc.stderr and "--overwrite" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert csv_path.read_text() == "kept\n"
    proc = _cli("analyze", bag, "--overwrite")
    assert proc.returncode == 0, proc.stderr
    assert csv_path.read_text().startswith("signal") or "entry_sample_index" in csv_path.read_text()


@pytest.mark.process
def test_analyze_never_writes_over_its_input_even_with_overwrite(recording, tmp_path):
    bag = tmp_path / "run.mcap"
    bag.write_bytes(recording.read_bytes())
    before = _digest(bag)
    proc = _cli("analyze", bag, "--out", tmp_path / "run", "--overwrite")   # run.mcap = the input
    assert proc.returncode == 2
    assert "is the input" in proc.stderr and "Traceback" not in proc.stderr
    assert _digest(bag) == before


@pytest.mark.process
@pytest.mark.ros
def test_record_refuses_an_existing_bag_and_replaces_it_only_when_told(recording, tmp_path, ros_env):
    bag = tmp_path / "old.mcap"
    bag.write_bytes(recording.read_bytes())
    before = _digest(bag)
    proc = _cli("record", "--output", bag, "--duration", "0.3", env=ros_env, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert "exists already" in proc.stderr and "Traceback" not in proc.stderr
    assert _digest(bag) == before
    proc = _cli("record", "--output", bag, "--duration", "0.3", "--overwrite", env=ros_env,
                timeout=120)
    # nothing was published: the recording is written, with a warning and exit code 1 (docs/cli.md)
    assert proc.returncode == 1, proc.stderr
    assert "recorded nothing" in proc.stderr and "Traceback" not in proc.stderr
    assert _digest(bag) != before
    assert not partial_path(bag).exists()
    with BagReader(bag) as reader:   # a complete (empty: nothing was published) recording
        assert "/plant/a1" not in reader.topics


@pytest.mark.process
@pytest.mark.ros
def test_pipeline_record_refuses_an_existing_bag(recording, tmp_path, ros_env):
    bag = tmp_path / "old.mcap"
    bag.write_bytes(recording.read_bytes())
    proc = _cli("pipeline", "--duration", "0.5", "--record", bag, env=ros_env, timeout=120)
    assert proc.returncode == 2
    assert "exists already" in proc.stderr and "Traceback" not in proc.stderr
    assert bag.read_bytes() == recording.read_bytes()


def test_staged_outputs_renames_only_complete_outputs(tmp_path):
    final = tmp_path / "out.csv"
    final.write_text("old")
    with pytest.raises(RuntimeError):
        with staged_outputs([final]) as (tmp,):
            tmp.write_text("half")
            raise RuntimeError("interrupted")
    assert final.read_text() == "old" and not partial_path(final).exists()
    with staged_outputs([final]) as (tmp,):
        tmp.write_text("new")
        assert final.read_text() == "old"   # not visible before the block completes
    assert final.read_text() == "new"


def test_check_outputs_names_the_problem(tmp_path):
    existing = tmp_path / "a.mcap"
    existing.write_text("x")
    with pytest.raises(OutputError, match="exists already"):
        check_outputs([existing])
    check_outputs([existing], overwrite=True)
    with pytest.raises(OutputError, match="is the input"):
        check_outputs([existing], inputs=[existing], overwrite=True)
    with pytest.raises(OutputError, match="directory"):
        check_outputs([tmp_path], overwrite=True)
