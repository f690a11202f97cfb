"""The live fleet's pickup of a drive's new version, its plain core (fleet/registry_pickup.py): which drives changed
in the registry, and only those; what their chains are sent; a version with a missing file is refused."""
import os

from backlash_monitor.fleet.drives import load_drives
from backlash_monitor.fleet.registry_pickup import FileChange, back_steps, changed, plan, versions
from backlash_monitor.files import registry

FLEET = """\
defaults: {n1: 0.89}
lines:
  line1:
    drive01: {width_m: 0.005, seed: 1}
    drive02: {width_m: 0.0075, seed: 2}
  line2:
    drive03: {width_m: 0.005, seed: 3, library: old3.npz}
"""


def fleet_file(tmp_path):
    path = tmp_path / "drives.yaml"
    path.write_text(FLEET)
    for name in ("old3.npz", "v2.npz", "v2.watch.npz"):
        (tmp_path / name).write_bytes(b"x")
    return path


def test_only_the_drive_registered_anew_has_changed_and_its_chain_gets_the_new_version(tmp_path):
    path = fleet_file(tmp_path)
    before = versions(load_drives(str(path)))
    assert changed(before, before) == []
    registry.register(path, "line1/drive02", model=tmp_path / "v2.yaml", library=tmp_path / "v2.npz",
                      watch_reference=tmp_path / "v2.watch.npz")
    after = versions(load_drives(str(path)))
    assert changed(before, after) == ["line1/drive02"]
    assert after["line1/drive02"].version == 2 and before["line1/drive02"].version == 1
    assert after["line2/drive03"] == before["line2/drive03"]      # its library, reference and version unchanged

    pickup = plan(before, after, watched={})
    assert list(pickup.swaps) == ["line1/drive02"] and not pickup.refused
    old, new, steps = pickup.swaps["line1/drive02"]
    assert [str(s) for s in steps if s.transition] == ["deactivate", "cleanup", "configure", "activate"]
    parameters = dict(next(s.parameters for s in steps if s.parameters))
    assert parameters == {"library": str(tmp_path / "v2.npz"), "watch_reference": str(tmp_path / "v2.watch.npz"),
                          "model_version": 2}
    # a configure that fails goes back to the old version's parameters (the packaged library: "")
    back = back_steps(old)
    assert dict(back[0].parameters) == {"library": "", "watch_reference": "", "model_version": 1}
    assert [s.transition for s in back[1:]] == ["configure", "activate"]


def test_the_same_files_registered_again_are_a_new_version(tmp_path):
    """train --drive overwrites a version's files in place: the registration, not the file names, makes it new."""
    path = fleet_file(tmp_path)
    registry.register(path, "drive01", library=tmp_path / "v2.npz")
    before = versions(load_drives(str(path)))
    registry.register(path, "drive01", library=tmp_path / "v2.npz")
    after = versions(load_drives(str(path)))
    assert changed(before, after) == ["line1/drive01"] and after["line1/drive01"].version == 3


def test_a_version_with_a_missing_file_is_refused_and_the_drive_is_not_touched(tmp_path):
    path = fleet_file(tmp_path)
    before = versions(load_drives(str(path)))
    registry.register(path, "drive03", library=tmp_path / "gone.npz", watch_reference=tmp_path / "gone.watch.npz")
    after = versions(load_drives(str(path)))
    pickup = plan(before, after, watched={"line2/drive03": False})
    assert not pickup.swaps and list(pickup.refused) == ["line2/drive03"]
    new, reason = pickup.refused["line2/drive03"]
    assert new.version == 2 and "gone.npz does not exist" in reason
    assert "watch reference" not in reason                     # not watched: its reference is not used
    reason_watched = plan(before, after, watched={"line2/drive03": True}).refused["line2/drive03"][1]
    assert "gone.watch.npz does not exist" in reason_watched


def test_after_a_refusal_the_next_version_swaps_from_the_version_the_drive_runs(tmp_path):
    path = fleet_file(tmp_path)
    running = versions(load_drives(str(path)))
    registry.register(path, "drive03", library=tmp_path / "gone.npz")
    seen = versions(load_drives(str(path)))                       # refused: the drive runs version 1
    registry.register(path, "drive03", library=tmp_path / "v2.npz")
    after = versions(load_drives(str(path)))
    old, new, _ = plan(seen, after, watched={}, running=running).swaps["line2/drive03"]
    assert old.version == 1 and old.library == str(tmp_path / "old3.npz") and new.version == 3


def test_drives_added_or_removed_are_named_not_started(tmp_path):
    path = fleet_file(tmp_path)
    before = versions(load_drives(str(path)))
    path.write_text(FLEET.replace("drive02: {width_m: 0.0075, seed: 2}", "drive09: {seed: 9}"))
    pickup = plan(before, versions(load_drives(str(path))), watched={})
    assert not pickup.swaps and not pickup.refused
    assert any("line1/drive09: added" in n for n in pickup.notes)
    assert any("line1/drive02: no longer" in n for n in pickup.notes)


def test_a_rewritten_file_is_seen_once(tmp_path):
    path = fleet_file(tmp_path)
    watch = FileChange(str(path))
    assert not watch.changed()
    registry.register(path, "drive01", library=tmp_path / "v2.npz")   # written beside and renamed
    assert watch.changed() and not watch.changed()
    os.remove(path)
    assert not watch.changed()                                       # gone (mid-rename): no change to read
