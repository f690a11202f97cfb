"""List the imports that sit inside a function or method body in `backlash_monitor/`.

    python tools/function_imports.py [--list] [--check] [--exclude PATH ...] [ROOT]

An import belongs at its module's top, so that a file's top shows what it uses (docs/architecture.md
"Imports at the top"). One inside a function is allowed only with a reason on the line just above it:

    # deferred: <module> costs ~N ms at start-up (python -X importtime, 29 Nov)
    # deferred: <reason>

Prints one line per function-level import with ``--list`` (``file:line  module  [deferred|BARE]``),
then a summary: how many imports the package has (module level and function level, internal and
third-party), and how many of the function-level ones carry a ``# deferred:`` comment. ``--check``
exits 1 if any function-level import lacks one (the files and folders given by ``--exclude``,
relative to the repository, are not checked; they are still counted). Standard library `ast` only.
"""
from __future__ import annotations

import argparse
import ast
import sys
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PACKAGE = "backlash_monitor"
DEFERRED_MARK = "# deferred:"


@dataclass(frozen=True)
class ImportSite:
    """One import statement: where it is, what it imports, and whether it is in a function."""

    path: Path
    line: int
    module: str
    internal: bool
    in_function: bool
    deferred: bool


def _imported_module(node: ast.Import | ast.ImportFrom, module_name: str, is_package: bool) -> str:
    """The absolute dotted name an import statement loads (its first name for ``import a, b``)."""
    if isinstance(node, ast.Import):
        return ", ".join(alias.name for alias in node.names)
    if node.level == 0:
        return node.module or ""
    parts = module_name.split(".")
    base = parts if is_package else parts[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _module_name(path: Path, root: Path) -> tuple[str, bool]:
    rel = path.relative_to(root.parent).with_suffix("")
    parts = list(rel.parts)
    is_package = parts[-1] == "__init__"
    if is_package:
        parts = parts[:-1]
    return ".".join(parts), is_package


def _has_deferred_comment(lines: list[str], line: int) -> bool:
    """Whether the line just above ``line`` (1-based) is a ``# deferred:`` comment."""
    return line >= 2 and lines[line - 2].strip().startswith(DEFERRED_MARK)


def import_sites(path: Path, root: Path) -> list[ImportSite]:
    """Every import statement of one file, each marked as module level or inside a function."""
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    module_name, is_package = _module_name(path, root)
    sites: list[ImportSite] = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                module = _imported_module(child, module_name, is_package)
                sites.append(ImportSite(
                    path=path, line=child.lineno, module=module,
                    internal=module.split(".")[0] == PACKAGE or (
                        isinstance(child, ast.ImportFrom) and child.level > 0),
                    in_function=in_function,
                    deferred=in_function and _has_deferred_comment(lines, child.lineno)))
            visit(child, in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

    visit(ast.parse(text, filename=str(path)), False)
    return sites


def package_sites(root: Path) -> list[ImportSite]:
    return [site for path in sorted(root.rglob("*.py")) for site in import_sites(path, root)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", nargs="?", type=Path, default=REPO / PACKAGE,
                        help=f"the package's directory (default: {PACKAGE}/ of this repository)")
    parser.add_argument("--list", action="store_true", help="one line per function-level import")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 if a function-level import lacks a '# deferred:' comment")
    parser.add_argument("--exclude", nargs="*", default=[], metavar="PATH",
                        help="files or folders (relative to the repository) that --check skips")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    if not root.is_dir():
        print(f"function_imports: {args.root} is not a directory (give the package's directory)", file=sys.stderr)
        return 2
    excluded = {(REPO / p).resolve() for p in args.exclude}

    def is_excluded(path: Path) -> bool:
        return path in excluded or any(e in path.parents for e in excluded)

    sites = package_sites(root)
    in_function = [s for s in sites if s.in_function]
    bare = [s for s in in_function if not s.deferred and not is_excluded(s.path)]
    if args.list:
        for s in in_function:
            mark = "deferred" if s.deferred else ("excluded" if is_excluded(s.path) else "BARE")
            print(f"{s.path.relative_to(root.parent)}:{s.line}  {s.module}  [{mark}]")
    internal = [s for s in sites if s.internal]
    print(f"imports: {len(sites)} ({len(internal)} internal); "
          f"inside functions: {len(in_function)} "
          f"({sum(s.internal for s in in_function)} of {len(internal)} internal, "
          f"{sum(not s.internal for s in in_function)} of {len(sites) - len(internal)} third-party/stdlib); "
          f"with '# deferred:': {sum(s.deferred for s in in_function)}; "
          f"without, not excluded: {len(bare)}")
    if args.check and bare:
        for s in bare:
            print(f"{s.path.relative_to(root.parent)}:{s.line}: import of {s.module} inside a function "
                  f"without a '# deferred: <reason>' comment on the line above", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
