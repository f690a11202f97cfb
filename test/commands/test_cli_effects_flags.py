"""One meaning per flag: --effects-file is a Python file of your own effects in every command;
diagnose's list of catalogue effects is --candidates. The old spellings (--effects FILE in
simulate/pipeline, --effects NAMES in diagnose) work for one release, with one line on stderr."""
import argparse

import pytest

from backlash_monitor.commands import diagnose, simulate
from backlash_monitor.nodes import pipeline


def parser_of(add_arguments, prog):
    p = argparse.ArgumentParser(prog=prog)
    add_arguments(p)
    return p


@pytest.mark.ros
@pytest.mark.parametrize("module, dest", [(simulate, "effects_file"), (pipeline, "effects_files")])
def test_effects_file_is_the_python_file_and_the_old_spelling_is_deprecated(module, dest, capsys):
    p = parser_of(module.add_arguments, module.__name__)
    new = p.parse_args(["--effects-file", "a.py", "--effects-file", "b.py"])
    assert getattr(new, dest) == ["a.py", "b.py"]
    assert capsys.readouterr().err == ""
    old = p.parse_args(["--effects", "a.py", "--effects-file", "b.py", "--effects", "c.py"])
    assert getattr(old, dest) == ["a.py", "b.py", "c.py"]        # the same meaning as before
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("--effects is deprecated" in e and "use --effects-file" in e for e in err)


@pytest.mark.ros
def test_diagnose_candidates_and_the_old_spelling(capsys):
    p = parser_of(diagnose.add_arguments, "diagnose")
    assert p.parse_args(["m.mcap", "--candidates", "wheel_drag,spring"]).candidates == "wheel_drag,spring"
    assert capsys.readouterr().err == ""
    assert p.parse_args(["m.mcap", "--effects", "wheel_drag"]).candidates == "wheel_drag"
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--effects is deprecated" in err[0] and "use --candidates" in err[0]
    # --effects-file is the workbench's file of plug-ins here too, not an abbreviation of anything
    assert p.parse_args(["m.mcap", "--effects-file", "mine.py"]).effects_file == ["mine.py"]


@pytest.mark.ros
def test_diagnose_refuses_a_python_file_as_a_candidate_naming_effects_file(tmp_path, capsys):
    from backlash_monitor.__main__ import main
    code = main(["diagnose", str(tmp_path / "m.mcap"), "--candidates", "my_effects.py",
                 "--json", str(tmp_path / "d.json")])
    err = capsys.readouterr().err
    assert code == 2
    assert "--effects-file my_effects.py" in err and "Traceback" not in err
