"""python -m foreign_drives: write a suite of foreign drive recordings (one file per recording + manifest.json)."""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from . import forms as F
from .spec import manifest
from .suites import SUITE_NAMES

# every suite `suite()` makes (suites.SUITE_NAMES: the named suites, then the sealed halves made on first use)
SUITE_CHOICES = SUITE_NAMES

DESCRIPTION = """\
Foreign drives: recordings of the drive made by a second, independent simulator (docs/foreign_drives.md),
with effects of the model catalogue's families written in other functional forms, and effects outside
the catalogue. Each recording's truth (true width, the catalogue family a user should be told about, the
catalogue-equivalent parameters) goes into manifest.json, never into the recording itself.

commands:
  write   make a suite's recordings into --out: one MCAP bag (or NPZ/CSV table) per recording, named
          <label>.<format>, and manifest.json (every spec, its truth, its file, its true entries)
  list    print a suite's recordings: label, kind, nominal width/eta_k/n1, effects and their families
  forms   print every effect form: name, family (None = outside the catalogue), stage, parameters, physics

examples:
  python -m foreign_drives write --suite bench --out foreign_bench
  python -m foreign_drives write --suite test --out /tmp/ft --only t_clean_w5 --format npz
  python -m foreign_drives list --suite widthloop
  python -m foreign_drives write --suite outside_dev --out outside_dev
"""


class _Parser(argparse.ArgumentParser):
    def error(self, message):                     # one line, exit 2
        sys.stderr.write(f"foreign_drives: error: {message}\n")
        sys.exit(2)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="python -m foreign_drives", description=DESCRIPTION,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", metavar="{write,list,forms}", parser_class=_Parser)
    w = sub.add_parser("write", help="make a suite's recordings into a directory",
                       description="Make a suite's recordings: one file per recording in --out, and manifest.json.")
    w.add_argument("--suite", required=True, choices=SUITE_CHOICES,
                   help="bench: >= 30 recordings of 4 s (seeds 5000+) for bench/workbench.py; widthloop: the "
                        "hidden-effect drives whose monitor width is checked before/after retraining (seeds 6000+); "
                        "test: short recordings the tests use (seeds 100-199); outside_dev / outside_sealed: "
                        "mechanisms outside the catalogue, development and sealed half (seeds 7000+ / 7100+); "
                        "outside_dev2 / outside_sealed2: a second set of other kinds (seeds 7300+ / 7400+); "
                        "outside_dev3 / outside_sealed3: a third set (seeds 7800+ / 7900+); outside_dev4 / "
                        "outside_sealed4: a fourth set (seeds 8000+ / 8100+); outside_dev5 / outside_sealed5: a fifth "
                        "(seeds 8200+ / 8300+); outside_dev6 / outside_sealed6: a sixth (seeds 8400+ / 8500+); "
                        "outside_dev7 / outside_sealed7: a seventh (seeds 8600+ / 8700+); outside_dev8 / "
                        "outside_sealed8: an eighth (seeds 8800+ / 8900+); outside_dev9 / outside_sealed9: a ninth (seeds "
                        "9000+ / 9100+); outside_dev10 / outside_sealed10: a tenth (seeds 10000+ / 10100+); outside_dev11 / "
                        "outside_sealed11: an eleventh (seeds 11000+ / 11100+); outside_dev12 / outside_sealed12: a "
                        "twelfth (seeds 12000+ / 12100+); outside_dev13 / outside_sealed13: a thirteenth (seeds 13000+ / "
                        "13100+); outside_dev14 / outside_sealed14: a fourteenth (seeds 14000+ / 14100+); outside_dev15 / "
                        "outside_sealed15: a fifteenth (seeds 15000+ / 15100+); outside_dev16 / outside_sealed16: a "
                        "sixteenth (seeds 16000+ / 16100+); outside_dev17 / outside_sealed17: a seventeenth (seeds "
                        "17000+ / 17100+)")
    w.add_argument("--out", required=True, metavar="DIR", help="output directory (created if missing)")
    w.add_argument("--only", action="append", metavar="LABEL", default=None,
                   help="write only this recording (repeatable); the manifest then lists only these")
    w.add_argument("--format", choices=("mcap", "npz", "csv"), default="mcap",
                   help="mcap: a rosbag2-style MCAP bag (default); npz/csv: the tables of docs/workbench.md")
    w.add_argument("--overwrite", action="store_true",
                   help="replace files that exist (default: refuse before any work)")
    w.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    ls = sub.add_parser("list", help="print a suite's recordings", description="Print a suite's recordings.")
    ls.add_argument("--suite", required=True, choices=SUITE_CHOICES, help="the suite")
    ls.add_argument("--json", action="store_true", help="the specs and truths as JSON (the manifest's content)")
    sub.add_parser("forms", help="print every effect form", description="Print every effect form.")
    return p


class Progress:
    """A progress bar on stderr (one line redrawn on a terminal, one line per step otherwise)."""

    def __init__(self, total: int, quiet: bool = False):
        self.total, self.done, self.quiet = total, 0, quiet
        self.tty = sys.stderr.isatty()
        self.t0 = time.monotonic()

    def step(self, label: str) -> None:
        self.done += 1
        if self.quiet:
            return
        n = 30
        full = int(n * self.done / max(self.total, 1))
        line = (f"[{'#' * full}{'.' * (n - full)}] {self.done}/{self.total} {time.monotonic() - self.t0:6.1f} s  "
                f"{label}")
        if self.tty:
            sys.stderr.write("\r" + line[:120].ljust(120))
            if self.done == self.total:
                sys.stderr.write("\n")
        else:
            sys.stderr.write(line + "\n")
        sys.stderr.flush()


def cmd_write(args) -> int:
    from .drive import make_recording
    from .files import write_bag, write_csv, write_npz
    from .suites import suite
    specs = suite(args.suite)
    if args.only:
        labels = {s.label for s in specs}
        bad = [x for x in args.only if x not in labels]
        if bad:
            raise ValueError(f"--only {bad[0]!r} is not in suite {args.suite}; allowed: {', '.join(sorted(labels))}")
        specs = [s for s in specs if s.label in args.only]
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {out} exists and is not a directory")
    targets = {s.label: out / f"{s.label}.{args.format}" for s in specs}
    man = out / "manifest.json"
    existing = [p for p in list(targets.values()) + [man] if p.exists()]
    if existing and not args.overwrite:
        raise ValueError(f"{existing[0]} exists ({len(existing)} file(s) would be replaced); allowed: a new "
                         "directory, or --overwrite")
    out.mkdir(parents=True, exist_ok=True)
    writer = {"mcap": write_bag, "npz": write_npz, "csv": write_csv}[args.format]
    bar = Progress(len(specs), args.quiet)
    made = {}
    for s in specs:
        rec = make_recording(s)
        writer(s, targets[s.label], recording=rec, overwrite=True)
        made[s.label] = rec.summary()
        bar.step(s.label)
    doc = manifest(specs, {k: v.name for k, v in targets.items()})
    for r in doc["recordings"]:
        r["made"] = made[r["spec"]["label"]]
    doc["suite"] = args.suite
    doc["format"] = args.format
    tmp = man.with_name(man.name + ".partial")
    tmp.write_text(json.dumps(doc, indent=1) + "\n")
    tmp.replace(man)
    print(f"wrote {len(specs)} recording(s) and {man}")
    return 0


def cmd_list(args) -> int:
    from .suites import suite
    specs = suite(args.suite)
    if args.json:
        print(json.dumps(manifest(specs), indent=1))
        return 0
    print(f"{'label':36s} {'kind':8s} {'width':>6s} {'eta_k':>7s} {'n1':>5s}  effects (form -> family)")
    for s in specs:
        eff = "; ".join(f"{e.form} -> {F.get(e.form).family}" for e in s.effects) or "-"
        print(f"{s.label:36s} {s.kind:8s} {s.width_m * 1e3:5.2f}mm {s.eta_k:7.4f} {s.n1:5.3f}  {eff}")
    return 0


def cmd_forms(args) -> int:
    for f in F.FORMS.values():
        params = ", ".join(f"{p.name} [{p.unit}]" if p.unit else p.name for p in f.parameters)
        if getattr(f, "half", "").startswith("sealed"):       # the sealed half's laws are not shown (issue 31 part 4)
            print(f"{f.name}  family=None  outside (sealed)  balance={f.balance}\n    law withheld: the sealed "
                  "half of the outside mechanisms")
            continue
        where = f"  balance={f.balance}  depends on {', '.join(f.depends_on)}" if getattr(f, "balance", "") else ""
        print(f"{f.name}  family={f.family}  stage={f.stage}{where}\n    {f.description}\n    parameters: {params}")
        if f.note:
            print(f"    note: {f.note}")
    return 0


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    try:
        return {"write": cmd_write, "list": cmd_list, "forms": cmd_forms}[args.command](args)
    except (ValueError, FileExistsError, FileNotFoundError, OSError) as exc:
        sys.stderr.write(f"foreign_drives: error: {exc}\n")
        return 2
