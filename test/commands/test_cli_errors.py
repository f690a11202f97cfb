"""One error policy (docs/cli.md): one line `python -m backlash_monitor <command>: error: ...`, exit 2 for bad input and
1 for a failure while running, one range form naming the option, no traceback, no internal name; the folder of an
output file must exist. bench/reliability.py (--modules inputs --inputs every) runs the long table over every
command; these are its cases that once escaped."""
import dataclasses
import re

import numpy as np
import pytest

from backlash_monitor.__main__ import main

PREFIX = re.compile(r"^python -m backlash_monitor [a-z-]+: error: ")


def error_line(capsys) -> str:
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip() and "warning:" not in line]
    assert "Traceback" not in err
    assert len(lines) == 1, err
    assert PREFIX.match(lines[0]), lines[0]
    return lines[0]


@pytest.mark.parametrize("command", ["simulate", "diagnose"])
def test_an_effects_file_that_is_not_python_is_one_line_not_a_traceback(command, tmp_path, capsys):
    text = tmp_path / "notabag.txt"
    text.write_text("not python\n")
    argv = [command, "--effects-file", str(text)] + (["m.mcap"] if command == "diagnose" else [])
    assert main(argv) == 2
    line = error_line(capsys)
    assert "is not a Python file" in line and "AttributeError" not in line


def test_a_syntax_error_in_an_effects_file_names_the_line_not_the_exception_class(tmp_path, capsys):
    bad = tmp_path / "mine.py"
    bad.write_text("x = 1\ndef broken(:\n")
    assert main(["simulate", "--effects-file", str(bad)]) == 2
    line = error_line(capsys)
    assert "line 2" in line and "SyntaxError" not in line


def test_a_truncated_bag_is_a_failure_exit_1_naming_recover_without_internal_names(tmp_path, capsys):
    from bag_helpers import write_sample_bag
    bag = tmp_path / "whole.mcap"
    write_sample_bag(bag, n_chunks=40)
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(bag.read_bytes()[:bag.stat().st_size * 2 // 3])
    for argv in (["bag-info", str(cut)], ["analyze", str(cut), "--out", str(tmp_path / "est")]):
        assert main(argv) == 1, argv
        line = error_line(capsys)
        assert "incomplete" in line and "--recover" in line and "BagReader" not in line


@pytest.mark.parametrize("argv, expected", [
    (["simulate", "--widths", "0.0075,2"], "--widths 2: out of range, allowed 0..1 m"),
    (["simulate", "--duration", "0"], "--duration 0: out of range, allowed 0..3600 s"),
    (["compare", "m.mcap", "--width-m", "0.2"], "--width-m 0.2: out of range, allowed 0..0.05 m"),
    (["compare", "m.mcap", "--ensemble", "2"], "--ensemble 2: out of range, allowed 3..64"),
    (["train", "--duration", "100"], "--duration 100: out of range, allowed 0.5..60 s"),
])
def test_one_range_form_that_names_the_option(argv, expected, capsys):
    assert main(argv) == 2
    assert expected in error_line(capsys)


def test_the_folder_of_an_output_file_must_exist(tmp_path, capsys):
    assert main(["simulate", "--duration", "0.01", "-o", str(tmp_path / "nope" / "x.npz")]) == 2
    assert "the folder" in error_line(capsys) and not (tmp_path / "nope").exists()


def test_no_command_is_one_line_naming_the_commands(capsys):
    assert main([]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "give a command; allowed: add-effect, analyze" in err[0]


def test_a_model_that_gives_no_training_windows_at_a_grid_condition_is_one_line_not_a_traceback(
        tmp_path, capsys, monkeypatch):
    """A model whose effects stop the simulated drive crossing its backlash at one condition of the training grid
    (seen in the README's loop: an accepted proposal with the partial effect it sits on, at 7.5 mm and n1 0.89) leaves
    that condition without a window: `train` says which condition, exits 1, and writes nothing."""
    from backlash_monitor.classifier import training
    pattern = training.pattern_windows

    def no_windows_at_the_widest(ws, signal, n1, widths_m=training.K2_WIDTHS_M, **kw):
        # the real windows, less the widest width's: as a model that never crosses its backlash there
        keep = ~np.isclose(ws.width_m, max(widths_m))
        return pattern(dataclasses.replace(ws, **{f.name: getattr(ws, f.name)[keep] for f in dataclasses.fields(ws)
                                                  if np.ndim(getattr(ws, f.name)) and len(getattr(ws, f.name)) == len(keep)}),
                       signal, n1, widths_m, **kw)
    monkeypatch.setattr(training, "pattern_windows", no_windows_at_the_widest)
    out = tmp_path / "lib.npz"
    assert main(["train", "-o", str(out), "--seeds", "1000", "--duration", "0.5", "--no-progress"]) == 1
    line = error_line(capsys)
    widest_mm = 1e3 * max(training.K2_WIDTHS_M)
    assert f"gave no onset window at width {widest_mm:.2f} mm" in line and "does not cross its backlash there" in line
    assert not out.exists()
