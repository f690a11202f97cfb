"""Every command of `python -m backlash_monitor` explains itself and refuses bad input cleanly."""
import subprocess
import sys

import pytest

from backlash_monitor.__main__ import build_parser
from backlash_monitor.commands import discover_commands

COMMANDS = [module.NAME for module in discover_commands()]


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
