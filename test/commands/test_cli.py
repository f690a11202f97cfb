"""Every command of `python -m backlash_monitor` explains itself and refuses bad input cleanly."""
import subprocess
import sys
from pathlib import Path

import pytest

from backlash_monitor.__main__ import build_parser
from backlash_monitor.commands import discover_commands

COMMANDS = [module.NAME for module in discover_commands()]
REPO = Path(__file__).resolve().parents[2]     # a user's shell in the checkout


def _run(*args):
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *args],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.process
def test_top_level_help_lists_every_command():
    out = _run("--help")
    assert out.returncode == 0
    for name in COMMANDS:
        assert name in out.stdout


@pytest.mark.process
@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_has_help_that_explains_every_option(command):
    out = _run(command, "--help")
    assert out.returncode == 0, out.stderr
    assert "usage:" in out.stdout
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command").choices[command]
    for action in sub._actions:
        assert action.help and action.help.strip(), f"{command}: option {action.option_strings} has no help"


@pytest.mark.process
def test_unknown_command_is_an_error_not_a_traceback():
    out = _run("frobnicate")
    assert out.returncode == 2
    assert "invalid choice" in out.stderr and "Traceback" not in out.stderr


@pytest.mark.process
@pytest.mark.ros
def test_pipeline_refuses_an_out_of_range_width_with_the_allowed_range():
    out = _run("pipeline", "--width-m", "-1")
    assert out.returncode == 2
    assert "--width-m" in out.stderr and "allowed" in out.stderr
    assert "Traceback" not in out.stderr


def _without_the_build_env():
    """A shell where `source env.sh` was not run: no install/ on the path, no ROS variables but loopback DDS."""
    import os
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH", "COLCON_PREFIX_PATH",
                        "LD_LIBRARY_PATH", "_ROS_WHEELS_BOOTSTRAP_COMPLETE")}
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    return env


@pytest.mark.process
def test_help_needs_no_set_up_and_a_command_that_does_says_so_in_one_line():
    """Before `source env.sh` (the message package built into install/ not on the path): every command's help
    works, and a command that needs the messages ends with one line saying what to run, exit 1."""
    env = _without_the_build_env()
    for args in (["--help"], ["pipeline", "--help"], ["fleet", "--help"]):
        out = subprocess.run([sys.executable, "-m", "backlash_monitor", *args], capture_output=True, text=True,
                             timeout=120, env=env, cwd=REPO)
        assert out.returncode == 0 and "usage:" in out.stdout, (args, out.stderr[-2000:])
    out = subprocess.run([sys.executable, "-m", "backlash_monitor", "pipeline", "--duration", "1"],
                         capture_output=True, text=True, timeout=120, env=env, cwd=REPO)
    if out.returncode == 0:
        pytest.skip("the message package is installed where this Python finds it without env.sh")
    assert out.returncode == 1 and "Traceback" not in out.stderr, out.stderr[-2000:]
    assert "backlash_monitor_msgs" in out.stderr and "source env.sh" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
