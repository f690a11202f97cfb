"""One vocabulary across the command line (commands/vocabulary.py, docs/cli.md): an option name means the same
thing in every command -- a value or a flag, the same type, the same shape of value -- and every option's help
shows its real default once, never 'None' or an empty one. New options pass when they follow the vocabulary."""
import argparse
import re

import pytest

from backlash_monitor.commands import _args
from backlash_monitor.commands.vocabulary import SIMULATE_LISTS, TERMS, term_of

pytestmark = pytest.mark.ros      # record/replay/pipeline/fleet build their options from the nodes' (rclpy)


def command_parsers() -> dict:
    from backlash_monitor.__main__ import build_parser
    top = build_parser()
    sub = next(a for a in top._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def visible_options(parser):
    """(long option name, action) of every option a user sees in --help (old spellings are hidden)."""
    for action in parser._actions:
        if action.help is argparse.SUPPRESS or not action.option_strings or isinstance(action, argparse._HelpAction):
            continue
        longs = [s for s in action.option_strings if s.startswith("--")]
        yield longs[0], action


def shape(action) -> tuple:
    """What an option's name promises: a flag or a value, its type (a list of the same quantity counts as
    the quantity), and how many values per occurrence (repeating an option is fine)."""
    if action.nargs == 0:
        return ("flag",)
    kind = action.type
    if kind in (_args.float_list,):
        kind = float
    return ("value", getattr(kind, "__name__", str(kind)) if kind else "str", action.nargs)


def test_every_command_is_checked():
    parsers = command_parsers()
    assert {"simulate", "train", "evaluate", "diagnose", "compare", "add-effect", "history", "watch-reference",
            "analyze", "bag-info", "record", "replay", "pipeline", "fleet"} <= set(parsers)


def test_one_meaning_per_option_name_across_commands():
    seen: dict[str, tuple] = {}
    problems = []
    for command, parser in command_parsers().items():
        for name, action in visible_options(parser):
            s = shape(action)
            if name in seen and seen[name][1] != s:
                problems.append(f"{name}: {seen[name][0]} {seen[name][1]} but {command} {s}")
            seen.setdefault(name, (command, s))
    assert not problems, "\n".join(problems)


def test_options_follow_the_vocabulary():
    problems = []
    for command, parser in command_parsers().items():
        for name, action in visible_options(parser):
            term = term_of(name)
            if term is None:
                continue           # a command's own option, used nowhere else
            if (term.kind == "flag") != (action.nargs == 0):
                problems.append(f"{command} {name}: the vocabulary says {term.kind}")
                continue
            if term.kind == "value" and term.type is not None:
                allowed = {term.type} | ({SIMULATE_LISTS[name]} if name in SIMULATE_LISTS else set())
                if action.type not in allowed:
                    problems.append(f"{command} {name}: type {action.type} but the vocabulary's {term.type}")
            if term.kind == "value" and term.metavar is not None and action.metavar != term.metavar:
                # the metavar says the shape: FILE, PREFIX, DIR, a seed list S[,S...] vs an ensemble size N
                # a file may name its kind: FILE.npz, M2.yaml, REF.watch.npz
                if not (term.metavar == "FILE" and "." in str(action.metavar)):
                    problems.append(f"{command} {name}: metavar {action.metavar} but the vocabulary's "
                                    f"{term.metavar}")
    assert not problems, "\n".join(problems)


def test_the_old_meanings_are_gone_from_the_help():
    parsers = command_parsers()
    # a seed list is --seeds everywhere; the workbench's ensemble size is --ensemble
    for command in ("compare", "diagnose", "add-effect", "watch-reference"):
        opts = dict(visible_options(parsers[command]))
        assert "--seeds" not in opts and opts["--ensemble"].type is int
    for command in ("simulate", "train", "evaluate"):
        assert dict(visible_options(parsers[command]))["--seeds"].type is _args.seed_list
    # --json is a file; JSON on stdout is --format json
    for command in ("bag-info", "history"):
        opts = dict(visible_options(parsers[command]))
        assert "--json" not in opts and opts["--format"].choices == ("text", "json")
    # one progress switch
    for command, parser in parsers.items():
        assert "--quiet" not in dict(visible_options(parser)), command
    for command in ("simulate", "train", "evaluate", "diagnose", "compare", "watch-reference", "analyze"):
        assert "--no-progress" in dict(visible_options(parsers[command])), command


def test_help_shows_real_defaults_once_and_keeps_the_layout():
    problems = []
    for command, parser in command_parsers().items():
        for name, action in visible_options(parser):
            text = parser.formatter_class(parser.prog)._get_help_string(action) % {
                **vars(action), "prog": parser.prog} if action.help else ""
            if "(default: None)" in text or "(default: )" in text or "(default: [])" in text:
                problems.append(f"{command} {name}: {text[-40:]!r}")
            if text.count("(default:") > 1:
                problems.append(f"{command} {name}: two defaults")
            if action.nargs != 0 and action.default in (None, "") and "default" not in text and not action.required:
                problems.append(f"{command} {name}: default {action.default!r} not explained in its help")
    assert not problems, "\n".join(problems)


def test_descriptions_keep_their_line_breaks_and_the_top_help_cites_no_spec():
    from backlash_monitor.__main__ import build_parser
    parsers = command_parsers()
    for command in ("pipeline", "fleet"):
        description = parsers[command].description
        assert "\n" in description
        assert description.splitlines()[2] in parsers[command].format_help()     # the layout kept
    assert not re.search(r"SPEC|section \d", build_parser().format_help())


def test_the_vocabulary_is_documented():
    from pathlib import Path
    doc = (Path(__file__).resolve().parents[2] / "docs" / "cli.md").read_text()
    for name in TERMS:
        assert re.search(r"[`/]" + re.escape(name) + r"\b", doc), f"{name} missing from docs/cli.md"


def test_the_nominal_values_shown_are_the_default_model_s():
    from backlash_monitor.commands._workbench import DEFAULT_NOMINAL_SHOWN
    from backlash_monitor.workbench.model import DEFAULT_NOMINAL
    assert DEFAULT_NOMINAL_SHOWN == DEFAULT_NOMINAL


@pytest.mark.parametrize("command, old, new_dest, value", [
    (["diagnose", "m.mcap"], ["--seeds", "8"], "ensemble", 8),
    (["compare", "m.mcap"], ["--no-record"], "no_history", True),
    (["train"], ["--out", "x.npz"], "output", "x.npz"),
    (["watch-reference"], ["--out", "x.watch.npz"], "output", "x.watch.npz"),
    (["bag-info", "b.mcap"], ["--json"], "format", "json"),
    (["history"], ["--json"], "format", "json"),
    (["simulate"], ["--quiet"], "no_progress", True),
    (["fleet"], ["--summary-json", "s.json"], "summary_json", "s.json"),
    (["replay", "b.mcap"], ["--rate", "0"], "rate", 0.0),
    (["record"], ["--duration-s", "2"], "duration_s", 2.0),
])
def test_old_spellings_work_for_one_release_with_one_line(command, old, new_dest, value, capsys):
    parser = command_parsers()[command[0]]
    args = parser.parse_args(command[1:] + old)
    assert getattr(args, new_dest) == value
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"{old[0]} is deprecated" in err[0], err
