"""Config files: an unknown key is an error naming it and the nearest valid one; broken YAML is
one line with the file and line (windowing.yaml and the nodes' --params-file files)."""
import subprocess
import sys

import pytest

from backlash_monitor.windowing.faults import FaultLog, InputHealth
from backlash_monitor.ros.params_file import ParamsFileError, check_params_file, params_files
from backlash_monitor.windowing import load_windowing_config


def _file(tmp_path, text):
    path = tmp_path / "x.yaml"
    path.write_text(text)
    return path


@pytest.mark.ros
@pytest.mark.parametrize("text, needles", [
    ("/**:\n  ros__parameters:\n    warn_widht_m: 0.1\n", ["'warn_widht_m'", "did you mean 'warn_width_m'"]),
    ("/**/denoise:\n  ros__parameters:\n    fusion_events: 3\n", ["'fusion_events'", "node 'denoise'"]),
    ("/**/clasifier:\n  ros__parameters:\n    mode: shape\n", ["'clasifier'", "did you mean 'classifier'"]),
    ("/**:\n  ros_parameters:\n    mode: shape\n", ["ros__parameters"]),
    ("/**:\n  ros__parameters:\n    mode: [shape\n", [":4:1: broken YAML", "at line 3"]),
    ("- 1\n", ["not a mapping"]),
])
def test_bad_params_files_give_one_line_naming_the_problem(tmp_path, text, needles):
    with pytest.raises(ParamsFileError) as info:
        check_params_file(_file(tmp_path, text))
    message = str(info.value)
    assert "\n" not in message and str(tmp_path) in message
    for needle in needles:
        assert needle in message


@pytest.mark.ros
def test_the_packaged_params_files_and_ros_keys_pass(repo_root, tmp_path):
    for name in ("drive.yaml", "diagnostics.yaml"):
        check_params_file(repo_root / "config" / name)
    check_params_file(_file(tmp_path, "/line1/drive7/windowing:\n  ros__parameters:\n"
                                      "    use_sim_time: false\n    qos_overrides:\n"
                                      "      /plant/a1:\n        subscription: {depth: 5}\n"))


@pytest.mark.ros
def test_params_files_are_found_after_ros_args_only():
    argv = ["x", "--params-file", "no.yaml", "--ros-args", "-p", "a:=1", "--params-file", "a.yaml",
            "--params-file", "b.yaml", "--", "--params-file", "c.yaml"]
    assert params_files(argv) == ["a.yaml", "b.yaml"]


@pytest.mark.ros
@pytest.mark.parametrize("text, needles", [
    ("detector:\n  confirm_radd: 0.01\n", ["confirm_radd", "did you mean 'confirm_rad'"]),
    ("captur:\n  window_length: 2048\n", ["'captur'", "did you mean 'capture'"]),
    ("capture:\n  window_length: {value: 2048, unti: samples}\n", ["unti", "'unit'"]),
    ("detector:\n  confirm_rad: [0.01\n", [":3:1: broken YAML", "at line 2"]),
])
def test_bad_windowing_yaml_gives_one_line(tmp_path, text, needles):
    with pytest.raises(ValueError) as info:
        load_windowing_config(_file(tmp_path, text))
    assert "\n" not in str(info.value)
    for needle in needles:
        assert needle in str(info.value)


@pytest.mark.process
@pytest.mark.ros
def test_a_node_started_with_a_misspelled_params_file_stops_with_one_line(ros_env, tmp_path):
    path = _file(tmp_path, "/**/classifier:\n  ros__parameters:\n    eror_width_m: 0.01\n")
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor.nodes.classifier", "--ros-args",
                           "--params-file", str(path)], env=ros_env, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2
    lines = [line for line in proc.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "'eror_width_m'" in lines[0] and "'error_width_m'" in lines[0]


@pytest.mark.ros
def test_input_health_warns_while_faults_come_then_ok_then_stale():
    health, log = InputHealth(stale_after_s=2.0, fault_hold_s=10.0, what="chunks"), FaultLog()
    assert health.state(0.0)[0] == "STALE"            # nothing yet
    health.arrived(1.0)
    assert health.state(1.0) == ("OK", "")
    log.add("gap", "samples 5..9 (5) missing")
    assert health.update(1.0, log)
    health.arrived(1.5)
    assert health.state(1.5)[0] == "WARN" and "gap" in health.state(1.5)[1]
    for t in (3.0, 5.0, 7.0, 9.0, 11.0, 11.5):
        health.arrived(t)
    assert health.state(11.6) == ("OK", "")           # 10.6 s after the fault
    assert health.state(14.0)[0] == "STALE"           # 2.5 s without a chunk
    assert not health.update(14.0, log)               # no new fault
