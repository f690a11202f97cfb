"""Imports at a module's top (docs/architecture.md "Imports at the top"): an import inside a function carries
a ``# deferred: <reason>`` comment on the line above (a measured start-up cost, an optional package, an order
that matters), checked by tools/function_imports.py. The tool itself is tested on a package written here."""
from __future__ import annotations

import importlib.util
import sys
import textwrap
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

# Every module is checked (chain/ and denoise.py too, since the chain package landed).
NOT_CHECKED_YET: list[str] = []


def _tool():
    spec = importlib.util.spec_from_file_location("function_imports", REPO / "tools" / "function_imports.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module      # its dataclass looks its module up there
    spec.loader.exec_module(module)
    return module


def test_every_function_level_import_of_the_package_says_why_it_is_deferred(capsys):
    code = _tool().main(["--check", "--exclude", *NOT_CHECKED_YET])
    assert code == 0, capsys.readouterr().err


def _package(tmp_path: Path, body: str) -> Path:
    root = tmp_path / "backlash_monitor"
    root.mkdir()
    (root / "__init__.py").write_text("")
    (root / "mod.py").write_text(textwrap.dedent(body))
    return root


def test_the_check_fails_on_a_function_level_import_without_a_reason(tmp_path, capsys):
    root = _package(tmp_path, """\
        import os


        def f():
            import json
            return json, os
        """)
    assert _tool().main([str(root), "--check"]) == 1
    err = capsys.readouterr().err
    assert "mod.py:5" in err and "json" in err


def test_a_deferred_comment_passes_and_module_level_imports_are_not_counted(tmp_path, capsys):
    root = _package(tmp_path, """\
        import os
        from . import other


        class A:
            def f(self):
                # deferred: json is only an example here
                import json
                return json, os, other
        """)
    tool = _tool()
    assert tool.main([str(root), "--check"]) == 0
    sites = tool.package_sites(root)
    inside = [s for s in sites if s.in_function]
    assert [(s.module, s.line, s.deferred) for s in inside] == [("json", 8, True)]
    assert {s.module for s in sites if not s.in_function} == {"os", "backlash_monitor"}
