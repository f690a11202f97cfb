"""`python -m backlash_monitor watch-reference`: build the model watch's reference of a model version.

The reference (workbench/reference.py) is what the live model watch needs to run the workbench's consistency test
without simulating: the model's noise ensemble, the views, the predictions over the backlash width. ``train
--model M.yaml --out LIB.npz`` writes one beside the library (LIB.watch.npz); this command makes one for any model,
by default into the cache the model_watch node, ``fleet`` and ``pipeline --watch`` take the default model's from.
"""
from __future__ import annotations

import sys
import time

from backlash_monitor.commands import UsageError
from backlash_monitor.commands._workbench import (
    add_model_arguments,
    add_overwrite_argument,
    add_progress_argument,
    check_outputs,
    load,
)
from backlash_monitor.commands.vocabulary import deprecated

NAME = "watch-reference"
HELP = "build the live model watch's reference of a model version (~30 s; docs/model_watch.md)"
DESCRIPTION = ("Run the workbench's comparison and screening on a recording the model makes of itself and keep what "
               "the consistency test needs (noise ensemble, views, predictions over the backlash width), so that the "
               "model_watch node simulates nothing. Without --output the reference goes into the cache (.cache/watch/), "
               "where model_watch, fleet and pipeline --watch find the default model's at a drive's nominal width, "
               "eta_k and n1.")


def add_arguments(parser) -> None:
    add_model_arguments(parser, measurement=False)
    parser.add_argument("-o", "--output", default=None, metavar="REF.watch.npz",
                        help="where to write it (default: the cache, .cache/watch/; an existing file is refused "
                             "unless --overwrite)")
    deprecated(parser, "--out", "--output", "output", metavar="REF.watch.npz")
    add_overwrite_argument(parser)
    add_progress_argument(parser)


def run(args) -> int:
    # deferred: backlash_monitor.workbench.reference costs ~750 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench import reference
    if args.output is not None and not str(args.output).endswith(".npz"):
        raise UsageError(f"--output {args.output}: a reference is an .npz file; give a name ending in .watch.npz")
    if args.output is not None:
        check_outputs(args, [args.output], "--output")
    if args.output is None and args.ensemble != 6:
        raise UsageError(f"--ensemble {args.ensemble}: the cache holds references of 6 seeds (what model_watch, "
                         "fleet and pipeline take); give --output for another number")
    model, _ = load(args, measurement=False)
    t0 = time.perf_counter()
    if args.output is None:
        path = reference.cache_path(model)
        if path.is_file() and not args.overwrite:
            print(f"model reference of {model.label()} is cached already: {path}")
            return 0
        ref = _build(reference, model, args)
        path.parent.mkdir(parents=True, exist_ok=True)
        ref.save(path)
    else:
        ref = _build(reference, model, args)
        path = ref.save(args.output)
    print(f"model reference written: {path}")
    print(f"  model {model.label()}: width {model.nominal['width_m'] * 1e3:g} mm, eta_k {model.nominal['eta_k']:g}, "
          f"n1 {model.nominal['n1']:g}; {len(ref.seeds)} seeds x {ref.build_events} onset events, "
          f"{len(ref.candidates)} candidates, {len(ref.widths_m)} widths "
          f"{ref.widths_m[0] * 1e3:.3f}..{ref.widths_m[-1] * 1e3:.3f} mm; {time.perf_counter() - t0:.0f} s",
          file=sys.stdout)
    return 0


def _build(reference, model, args):
    """reference.build with a progress bar over its candidate screening (the ~30 s of the command)."""
    # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from tqdm import tqdm
    with tqdm(desc="model reference: screening candidate effects", unit="effect", file=sys.stderr,
              disable=True if args.no_progress else None) as bar:
        return reference.build(model, seeds=list(range(args.ensemble)), progress=bar.update)
