"""Pattern library: round trip, versioning and refusal of libraries made with other settings."""
import json

import numpy as np
import pytest

from backlash_monitor.classifier.patterns import (FORMAT_VERSION, TRIGGER_LIBRARY_PATHS, PatternLibrary,
                                                  PatternLibraryError, PatternLibraryMismatch, load_library,
                                                  read_npz)
from backlash_monitor.classifier.shape import ShapeModel

SETTINGS = {"trigger": "paper", "epochs": 30, "l1": 0.1, "l2": 0.09, "denoising": "sym5 level 6",
            "window_length": 64, "window_offset_samples": 400, "sample_period_s": 2e-5, "plant_config_hash": "abc"}


def _library(tmp_path):
    rng = np.random.default_rng(0)
    widths = np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01])
    arrays = {}
    for v in ("paper", "paper_corrected"):
        for s in ("a1", "a2"):
            arrays[f"{v}/{s}/m3"] = np.tile(np.linspace(-1, 1, 6), (5, 1))
            arrays[f"{v}/{s}/w5"] = rng.normal(size=(5, 6, 6))
    lib = PatternLibrary(settings=dict(SETTINGS), widths_m=widths, n1_values=np.array([0.89, 0.91, 0.93, 0.95, 0.97]),
                         arrays=arrays, training={"seeds": [1000]})
    return lib, lib.save(tmp_path / "lib.npz")


def test_round_trip_and_cpn(tmp_path):
    lib, path = _library(tmp_path)
    back = load_library(path, trigger="paper", epochs=30, l1=0.1, l2=0.09)
    assert back.modes == ["paper", "paper_corrected"]
    np.testing.assert_array_equal(back.arrays["paper/a1/w5"], lib.arrays["paper/a1/w5"])
    net = back.cpn("paper", "a2", 0.93)
    np.testing.assert_array_equal(net.w5, lib.arrays["paper/a2/w5"][2])
    assert (net.epochs, net.l1, net.l2) == (30, 0.1, 0.09)
    with np.load(path) as z:
        meta = json.loads(str(z["meta"]))
    assert meta["format_version"] == FORMAT_VERSION and meta["settings"]["trigger"] == "paper"


def test_refuses_other_settings_naming_each_mismatch(tmp_path):
    _, path = _library(tmp_path)
    with pytest.raises(PatternLibraryMismatch) as e:
        load_library(path, trigger="contact_loss", epochs=40)
    msg = str(e.value)
    assert "trigger: library has 'paper', requested 'contact_loss'" in msg
    assert "epochs: library has 30, requested 40" in msg
    assert set(e.value.mismatches) == {"trigger", "epochs"}
    load_library(path, trigger=None)      # None is not checked


def test_refuses_other_format_version(tmp_path):
    _, path = _library(tmp_path)
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    meta = json.loads(str(arrays["meta"]))
    meta["format_version"] = FORMAT_VERSION + 1
    arrays["meta"] = np.array(json.dumps(meta))
    np.savez(tmp_path / "v2.npz", **arrays)
    with pytest.raises(PatternLibraryMismatch, match="format_version"):
        load_library(tmp_path / "v2.npz")


def test_missing_unknown_and_bad_requests(tmp_path):
    with pytest.raises(PatternLibraryError, match="does not exist.*train"):
        load_library(tmp_path / "nope.npz")
    _, path = _library(tmp_path)
    with pytest.raises(ValueError, match="unknown library setting"):
        load_library(path, colour="red")
    lib = load_library(path)
    with pytest.raises(ValueError, match="allowed: 0.89, 0.91"):
        lib.cpn("paper", "a1", 0.90)
    with pytest.raises(ValueError, match="allowed: a1, a2"):
        lib.cpn("paper", "a3", 0.89)
    with pytest.raises(ValueError, match="allowed: paper, paper_corrected"):
        lib.cpn("shape", "a1", 0.89)
    del lib.arrays["paper/a2/w5"]
    with pytest.raises(PatternLibraryError, match="has no paper patterns for a2"):
        lib.cpn("paper", "a2", 0.89)


def test_shape_model_stored_and_restored(tmp_path):
    rng = np.random.default_rng(1)
    widths = np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01])
    model = ShapeModel(signal="a1", widths_m=widths, mu=rng.normal(size=8), sd=np.ones(8),
                       coef=rng.normal(size=8 + 36), intercept=0.005, sigma_m=2e-4, sample_period_s=2e-5)
    lib, _ = _library(tmp_path)
    lib.arrays.update(model.to_arrays())
    path = lib.save(tmp_path / "with_shape.npz")
    back = load_library(path)
    assert "shape" in back.modes
    m2 = ShapeModel.from_arrays({f"shape/{k}": v for k, v in back.shape_arrays().items()}, "a1", widths)
    np.testing.assert_array_equal(m2.coef, model.coef)
    assert m2.sigma_m == model.sigma_m


def test_refuses_another_window_offset(tmp_path):
    _, path = _library(tmp_path)
    load_library(path, trigger="paper", window_offset_samples=400)
    with pytest.raises(PatternLibraryMismatch, match="window_offset_samples: library has 400, requested 0"):
        load_library(path, trigger="paper", window_offset_samples=0)


def test_packaged_libraries_carry_the_configured_offset():
    from backlash_monitor.windowing import default_window_offset
    for trig in ("contact_loss", "paper"):
        lib = load_library(None, trigger=trig, window_offset_samples=default_window_offset(trig))
        assert lib.settings["window_offset_samples"] == default_window_offset(trig)


def _same_as_np_load(path):
    got = read_npz(path)
    with np.load(path, allow_pickle=False) as z:
        want = {k: z[k] for k in z.files}
    assert list(got) == list(want)
    for key, a in want.items():
        b = got[key]
        assert (b.dtype, b.shape, b.flags.f_contiguous) == (a.dtype, a.shape, a.flags.f_contiguous), key
        assert b.tobytes(order="A") == a.tobytes(order="A"), key
        assert b.flags.writeable, key


def test_read_npz_gives_what_np_load_gives(tmp_path):
    """read_npz parses numpy's plain headers itself: every array as np.load reads it (the packaged
    libraries, and the header forms numpy writes: Fortran order, 0-d, empty, big endian, unicode,
    bool, complex; a structured dtype goes through numpy's reader)."""
    for path in TRIGGER_LIBRARY_PATHS.values():
        _same_as_np_load(path)
    forms = {"fortran": np.asfortranarray(np.arange(12.0).reshape(3, 4)), "scalar": np.array(3.5),
             "empty": np.zeros((0, 3)), "one": np.arange(7.0), "big_endian": np.arange(4, dtype=">i8"),
             "text": np.array("héllo"), "flags": np.array([True, False]), "complex": np.arange(3) * 1j,
             "int8": np.arange(5, dtype=np.int8),
             "record": np.zeros(3, dtype=[("a", "<i4"), ("b", "<f8")])}
    for save in (np.savez, np.savez_compressed):
        path = tmp_path / f"{save.__name__}.npz"
        save(path, **forms)
        _same_as_np_load(path)


def test_unreadable_library_is_named(tmp_path):
    path = tmp_path / "lib.npz"
    path.write_bytes(b"PK not a zip file")
    with pytest.raises(PatternLibraryError, match="unreadable"):
        load_library(path)
