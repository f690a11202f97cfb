"""A live fleet picks up one drive's new model version: which drives changed in the registry, and what to send
their chains (docs/registry.md, "Live pickup"; docs/fleet.md).

Plain Python, no rclpy: the fleet's supervisor (nodes/registry_follower.py) reads the registry again when the file
changes, and this module says which drives' current version changed (and only those), whether the new version can be
taken at all (its files exist), and the steps of the swap over the standard lifecycle services of the drive's chain
``<ns>/chain``::

    set_parameters  library, watch_reference, model_version     (they take effect at the next configure)
    change_state    deactivate, cleanup, configure, activate     (the chain's nodes are rebuilt with them)

and, when the new version's configure fails (an unreadable library), the steps back to the old version.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

from backlash_monitor.fleet.drives import Drive

# the chain's parameters that hold one version of a drive (nodes/fleet.py routes them to its classifier and model
# watch); model_version is the registry's version number, reported in the classifier's diagnostics
CHAIN_VERSION_PARAMETERS = ("library", "watch_reference", "model_version")
SWAP_TRANSITIONS = ("deactivate", "cleanup")      # before the new parameters are set
TAKE_TRANSITIONS = ("configure", "activate")      # after


@dataclass(frozen=True)
class DriveVersion:
    """One drive's current version as the registry (the fleet file) names it; paths absolute, "" for none."""
    version: int
    model: str = ""
    library: str = ""
    watch_reference: str = ""
    registered_utc: str = ""

    @classmethod
    def of(cls, drive: Drive) -> "DriveVersion":
        p = drive.parameters
        versions = p.get("versions") or []
        return cls(version=len(versions) + 1 if isinstance(versions, list) else 1,
                   model=str(p.get("model") or ""), library=str(p.get("library") or ""),
                   watch_reference=str(p.get("watch_reference") or ""),
                   registered_utc=str(p.get("registered_utc") or ""))

    def chain_parameters(self) -> dict:
        """{chain parameter: value}: what the drive's chain is configured with for this version."""
        return {"library": self.library, "watch_reference": self.watch_reference, "model_version": self.version}

    def describe(self) -> str:
        def name(path: str) -> str:
            return os.path.basename(path) if path else "default"
        return (f"version {self.version} (model {name(self.model)}, library {name(self.library)}, "
                f"watch reference {name(self.watch_reference)})")


def versions(drives) -> dict[str, DriveVersion]:
    """{hardware id: its current version} of a fleet file's drives."""
    return {d.hardware_id: DriveVersion.of(d) for d in drives}


def changed(before: dict[str, DriveVersion], after: dict[str, DriveVersion]) -> list[str]:
    """The drives (hardware ids, sorted) that run before and are in the registry after, whose current version
    changed: another model, library, watch reference, version number or registration time (a version registered
    again under the same file names is new: train overwrites its files in place)."""
    return sorted(h for h in before if h in after and after[h] != before[h])


def not_followed(before: dict[str, DriveVersion], after: dict[str, DriveVersion]) -> list[str]:
    """One line per drive added to or removed from the registry: the fleet runs the drives it started with."""
    return ([f"{h}: added to the registry; not started (the fleet runs the drives it started with)"
             for h in sorted(set(after) - set(before))]
            + [f"{h}: no longer in the registry; kept running on its version" for h in sorted(set(before) - set(after))])


def missing_files(version: DriveVersion, watched: bool) -> list[str]:
    """The new version's files that do not exist (the watch reference only for a watched drive)."""
    paths = [("library", version.library)] + ([("watch reference", version.watch_reference)] if watched else [])
    return [f"{what} {path} does not exist" for what, path in paths if path and not os.path.isfile(path)]


@dataclass(frozen=True)
class Step:
    """One request to the drive's chain: a lifecycle transition (``transition``) or parameters to set."""
    transition: str = ""
    parameters: tuple = ()          # ((name, value), ...)

    def __str__(self) -> str:
        return self.transition or "set " + ", ".join(f"{k}={v}" for k, v in self.parameters)


def swap_steps(new: DriveVersion) -> list[Step]:
    """Deactivate, clean up, set the new version's parameters, configure (the chain checks them: a failure leaves
    it unconfigured, see :func:`back_steps`), activate. The plant is not touched."""
    return ([Step(transition=t) for t in SWAP_TRANSITIONS]
            + [Step(parameters=tuple(new.chain_parameters().items()))]
            + [Step(transition=t) for t in TAKE_TRANSITIONS])


def back_steps(old: DriveVersion) -> list[Step]:
    """After the new version's configure failed (the chain is unconfigured): the old version again."""
    return [Step(parameters=tuple(old.chain_parameters().items()))] + [Step(transition=t) for t in TAKE_TRANSITIONS]


@dataclass(frozen=True)
class Pickup:
    """What one reading of the registry asks of the running fleet."""
    swaps: dict          # hardware id -> (old DriveVersion, new DriveVersion, [Step])
    refused: dict        # hardware id -> (new DriveVersion, reason): the drive stays on its version
    notes: list          # lines about drives added or removed


def plan(before: dict[str, DriveVersion], after: dict[str, DriveVersion], watched: dict[str, bool],
         running: dict[str, DriveVersion] | None = None) -> Pickup:
    """The swaps for the drives whose version changed from the registry's last reading ``before`` (only those), and
    whose new files exist; the others refused with why. ``running``: the versions the drives run (default
    ``before``; after a refusal a drive runs an older one than the registry names)."""
    running = running or before
    swaps, refused = {}, {}
    for h in changed(before, after):
        missing = missing_files(after[h], watched.get(h, False))
        if missing:
            refused[h] = (after[h], "; ".join(missing))
        else:
            swaps[h] = (running.get(h, before[h]), after[h], swap_steps(after[h]))
    return Pickup(swaps, refused, not_followed(before, after))


class FileChange:
    """Says when a file changed since it was last asked: its (mtime_ns, size, inode), so a write-beside-and-rename
    is seen even within one mtime tick."""

    def __init__(self, path: str):
        self.path = path
        self.mark = self._stat()

    def _stat(self):
        try:
            s = os.stat(self.path)
        except OSError:
            return None
        return (s.st_mtime_ns, s.st_size, s.st_ino)

    def changed(self) -> bool:
        mark = self._stat()
        if mark is None or mark == self.mark:
            return False
        self.mark = mark
        return True
