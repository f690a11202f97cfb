"""Output files that never destroy data: no command writes over its input, nor over an existing
file unless the user says so (``--overwrite``); outputs are written under a temporary name in the
same directory and renamed onto their final name only once complete.

    check_outputs([out.csv, out.mcap], inputs=[bag], overwrite=args.overwrite)   # before any work
    with staged_outputs([out.csv, out.mcap]) as tmp:   # tmp[i]: where to write outputs[i]
        write(tmp[0]); write(tmp[1])
    # all renamed together on success; on an exception the partial files are removed

A crash between the renames can leave some outputs renamed and others not; none is ever half
written (``os.replace`` is atomic within one file system).
"""
from __future__ import annotations

import contextlib
import os
from pathlib import Path

PARTIAL_SUFFIX = ".partial"


class OutputError(ValueError):
    """An output path that would destroy data (the input, or an existing file without --overwrite)."""


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return False


# Options that name a folder of outputs: the folder is created if missing. The folder of an output
# file (-o/--output, --out PREFIX, --json, --record) must exist: a typo in it is refused, not made.
FOLDER_OPTIONS = ("--report", "--mcap")


def creates_folder(option: str) -> bool:
    return option.endswith("-dir") or option in FOLDER_OPTIONS


def missing_folder_message(option: str, out) -> str:
    out = Path(out)
    return (f"{option} {out}: the folder {out.parent} does not exist; create it first (only folder options "
            "such as --out-dir create their folder)")


def check_outputs(outputs, *, inputs=(), overwrite: bool = False, option: str = "--out") -> None:
    """Raise :class:`OutputError` naming the first output that is an input (never allowed) or that
    exists already while ``overwrite`` is false, or that is a directory, or whose folder does not
    exist while ``option`` names a file (not a folder option, :func:`creates_folder`)."""
    outputs = [Path(p) for p in outputs]
    inputs = [Path(p) for p in inputs]
    for out in outputs:
        if not creates_folder(option) and not out.parent.is_dir():
            raise OutputError(missing_folder_message(option, out))
        for source in inputs:
            if _same_file(out, source) or out.resolve() == source.resolve():
                raise OutputError(f"{option}: the output {out} is the input {source}; it would be "
                                  "overwritten: give another output path")
        if out.is_dir():
            raise OutputError(f"{option}: the output {out} is a directory; allowed: a file path")
        if out.exists() and not overwrite:
            raise OutputError(f"{option}: {out} exists already; pass --overwrite to replace it, "
                              "or give another path")


def partial_path(path) -> Path:
    """The temporary name an output is written under until it is complete (same directory)."""
    path = Path(path)
    return path.with_name(f"{path.name}{PARTIAL_SUFFIX}")


@contextlib.contextmanager
def staged_outputs(outputs):
    """Yield temporary paths for ``outputs``; rename them onto the outputs when the block ends
    without an exception, remove them when it raises."""
    outputs = [Path(p) for p in outputs]
    temps = [partial_path(p) for p in outputs]
    for out in outputs:
        out.parent.mkdir(parents=True, exist_ok=True)
    try:
        yield temps
    except BaseException:
        for tmp in temps:
            with contextlib.suppress(OSError):
                tmp.unlink()
        raise
    for tmp, out in zip(temps, outputs):
        if tmp.exists():
            os.replace(tmp, out)
