"""Derive test/data/mcap_conformance.json from the MCAP project's conformance corpus.

    python tools/derive_mcap_conformance.py MCAP_REPO [-o test/data/mcap_conformance.json]

MCAP_REPO: a checkout of github.com/foxglove/mcap or its bare git directory (the newest commit is
read). Its `tests/conformance/data/<Input>/<Input>-<features>.json` files describe each variant:
the records a writer is given (Header, Schema, Channel, Message, Attachment, Metadata) and the
variant's features (ch chunked, mx message indexes, chx chunk indexes, st statistics, rsh/rch
schemas/channels repeated in the summary, ax/mdx attachment/metadata indexes, sum summary offsets,
pad extra bytes in records). The `.mcap` files next to them are Git LFS pointers; the test writes
each variant again with the official `mcap` writer (test/mcap_conformance.py), as the corpus's
own Python writer test does (python/mcap/tests/run_writer_test.py).

The output holds each input's writer records once (they are the same in every variant of an
input; checked here) and every variant's name and features, without the `pad` variants (extra
bytes inside records: the Python writer cannot write them). No network: run it once on a fetched
copy; the test reads only the output.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

DATA = "tests/conformance/data"
WRITER_RECORDS = ("Header", "Schema", "Channel", "Message", "Attachment", "Metadata")


def _files(repo: Path) -> tuple[str, dict[str, str]]:
    """(commit or 'worktree', {relative path: text}) of the corpus's JSON files."""
    if (repo / DATA).is_dir():
        return "worktree", {str(p.relative_to(repo)): p.read_text()
                            for p in sorted((repo / DATA).rglob("*.json"))}
    git = ["git", f"--git-dir={repo}"]
    commit = subprocess.run(git + ["rev-parse", "HEAD"], check=True, capture_output=True,
                            text=True).stdout.strip()
    names = subprocess.run(git + ["ls-tree", "-r", "--name-only", commit, DATA], check=True,
                           capture_output=True, text=True).stdout.split()
    return commit, {n: subprocess.run(git + ["show", f"{commit}:{n}"], check=True,
                                      capture_output=True, text=True).stdout
                    for n in names if n.endswith(".json")}


def writer_records(records: list[dict]) -> list[dict]:
    """The records a writer is given, each schema and channel once (as run_writer_test.py does:
    the corpus lists the summary's repeated copies too)."""
    out, schemas, channels = [], set(), set()
    for r in records:
        if r["type"] not in WRITER_RECORDS:
            continue
        fields = dict(r["fields"])
        if r["type"] == "Schema":
            if fields["name"] in schemas:
                continue
            schemas.add(fields["name"])
        if r["type"] == "Channel":
            if fields["topic"] in channels:
                continue
            channels.add(fields["topic"])
        out.append({"type": r["type"], "fields": fields})
    return out


def derive(repo: Path) -> dict:
    commit, files = _files(repo)
    inputs: dict[str, list] = {}
    variants = []
    for path, text in sorted(files.items()):
        name = Path(path).stem
        base = name.split("-")[0]
        doc = json.loads(text)
        features = sorted(doc["meta"]["variant"]["features"])
        if "pad" in features:
            continue
        records = writer_records(doc["records"])
        if base in inputs and inputs[base] != records:
            raise SystemExit(f"{path}: its writer records differ from the other {base} variants")
        inputs[base] = records
        variants.append({"name": name, "input": base, "features": features})
    return {"source": f"github.com/foxglove/mcap {commit} {DATA} (without the pad variants)",
            "inputs": inputs, "variants": variants}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("repo", type=Path, help="foxglove/mcap checkout or bare git directory")
    ap.add_argument("-o", "--out", type=Path,
                    default=Path(__file__).resolve().parents[1] / "test/data/mcap_conformance.json")
    args = ap.parse_args(argv)
    result = derive(args.repo)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(result, indent=1, sort_keys=True) + "\n")
    print(f"{len(result['variants'])} variants of {len(result['inputs'])} inputs -> {args.out}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
