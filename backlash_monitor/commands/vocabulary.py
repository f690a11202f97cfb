"""The command line's vocabulary: one meaning per option name, in every command.

An option name means one thing wherever it appears: the same value type, the same number of values, the same
unit. ``TERMS`` lists the names more than one command uses, or that a new command is likely to use; a new option
follows it (same name for the same thing, another name for another thing). ``test/commands/test_cli_vocabulary.py``
checks every command's parser against it, and docs/cli.md documents it.

Name rules that hold beyond the list:

- ``-o/--output FILE``: the command's one output file; ``--out PREFIX``: a prefix several files are written under
  (PREFIX.csv, PREFIX.json, ...); ``--out-dir DIR`` (and any ``--...-dir DIR``): a folder, created if missing;
- ``--json FILE``: also write a JSON document to FILE; ``--format json``: print JSON on stdout instead of text;
- ``--seeds S[,S...]``: a list of noise seeds; ``--ensemble N``: the size of a model's noise ensemble; ``--seed N``:
  one seed;
- ``--no-...``: a switch that turns something off; ``--no-progress`` is the one progress switch;
- a unit is in the name (``--width-m``) or in the help's brackets (``[s]``).
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass

from backlash_monitor.commands._args import float_list, seed_list
from backlash_monitor.errors import HelpFormatter as _HelpFormatter, DeprecatedSpelling


@dataclass(frozen=True)
class Term:
    """One option name's meaning: ``kind`` 'flag' (no value) or 'value'; ``type`` the argparse type (None: str);
    ``metavar`` the shape of its value (None: any); ``meaning`` one line, with the unit."""
    kind: str
    type: object = None
    metavar: str | None = None
    meaning: str = ""


TERMS: dict[str, Term] = {
    # outputs
    "--output": Term("value", None, "FILE", "the command's one output file (-o)"),
    "--out": Term("value", None, "PREFIX", "a prefix the outputs are written under: PREFIX.csv, PREFIX.json, ..."),
    "--out-dir": Term("value", None, "DIR", "a folder for the outputs (created if missing)"),
    "--report": Term("value", None, "DIR", "a folder for an HTML report and its PNGs (created if missing)"),
    "--snapshot-dir": Term("value", None, "DIR", "a folder the model watch's snapshot bags go into"),
    "--trend-state-dir": Term("value", None, "DIR", "a folder of the drives' width-trend states"),
    "--mcap": Term("value", None, "DIR", "a folder for one MCAP bag per scenario (created if missing)"),
    "--record": Term("value", None, "FILE.mcap", "also record the run's topics into this MCAP file"),
    "--json": Term("value", None, "FILE", "also write the result as JSON to FILE"),
    "--format": Term("value", None, None, "what is printed on stdout: text (default) or json"),
    "--overwrite": Term("flag", meaning="replace output files that exist (default: refuse, naming the file)"),
    # seeds
    "--seeds": Term("value", seed_list, "S[,S...]", "noise seeds: a comma-separated list of integers >= 0"),
    "--ensemble": Term("value", int, "N", "size of the model's noise ensemble (seeds 0..N-1)"),
    "--seed": Term("value", int, "N", "one seed (integer >= 0)"),
    "--noise-seed": Term("value", int, "N", "one seed for common random numbers"),
    # time
    "--duration": Term("value", float, "S", "seconds of signal (simulated or recorded) [s]"),
    "--rate-factor": Term("value", float, "X", "seconds of signal per wall second; 0 = as fast as the consumers "
                                               "take it (only where a command can; else refused)"),
    # the drive
    "--width-m": Term("value", float, "M", "the drive's backlash width [m]"),
    "--eta-k": Term("value", None, None, "absorber consistency eta_k [Pa*s^n] (simulate: a list)"),
    "--n1": Term("value", None, None, "absorber flow index n1 [-] (simulate: a list)"),
    "--namespace": Term("value", None, None, "namespace of the drive's topics in a bag"),
    # models and libraries
    "--model": Term("value", None, "M.yaml", "a workbench model version (YAML)"),
    "--library": Term("value", None, None, "a pattern library (.npz)"),
    "--set": Term("value", None, "SECTION.KEY=VALUE", "one plant config override; repeatable"),
    "--effects-file": Term("value", None, "FILE.py", "a Python file of your own Effect classes; repeatable"),
    "--config": Term("value", None, None, "a configuration file (YAML)"),
    "--trigger": Term("value", None, None, "the backlash-entry trigger: contact_loss or paper"),
    "--mode": Term("value", None, None, "the classifier mode"),
    "--window-offset": Term("value", int, "SAMPLES", "samples from the detected entry to the window start"),
    "--fusion-events": Term("value", int, None, "onset events fused into one estimate"),
    "--recover": Term("flag", meaning="read what is intact of a damaged bag and say what was skipped"),
    "--topics": Term("value", None, None, "comma-separated topic names"),
    "--jobs": Term("value", int, None, "work items run at once (0: this machine's cores)"),
    # switches
    "--no-progress": Term("flag", meaning="no progress bar (the one progress switch)"),
    "--no-plots": Term("flag", meaning="write no PNG plots"),
    "--no-history": Term("flag", meaning="do not add this check to the model's history"),
}

SIMULATE_LISTS = {"--eta-k": float_list, "--n1": float_list}   # simulate's grid: lists of the same quantities


def term_of(option: str) -> Term | None:
    """The vocabulary's entry of a long option name (``--out-dir``), or the rule that covers it."""
    if option in TERMS:
        return TERMS[option]
    if option.endswith("-dir"):
        return Term("value", None, "DIR", "a folder")
    if option.startswith("--no-"):
        return Term("flag", meaning="switch something off")
    return None


HelpFormatter = _HelpFormatter   # the help format of every command (errors.py: the executables share it)


def deprecated(parser, old: str, new: str, dest: str, **kwargs) -> None:
    """Take ``old``, an option's spelling of the release before, into ``dest`` for one more release, with one
    line on stderr naming ``new`` (errors.DeprecatedSpelling; hidden from --help)."""
    parser.add_argument(old, dest=dest, action=DeprecatedSpelling, new=new, help=argparse.SUPPRESS, **kwargs)
