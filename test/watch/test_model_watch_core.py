"""The model watch's cores: the precomputed model reference against diagnose's own consistency test, the width as
the measurand, the live onset events against the workbench's, the alarm rule, the watch on a stream whose plant
changes mid-run (docs/model_watch.md)."""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario
from backlash_monitor.watch.alarm import AlarmRule, AlarmState
from backlash_monitor.watch.core import ModelWatch, evaluate_recording
from backlash_monitor.watch.events import LiveEvents, SampleRing
from backlash_monitor.workbench import diagnose, plant_adapter, reference, synthetic
from backlash_monitor.workbench.events import DC_SIGNALS, SEGMENT_SIGNALS, event_set
from backlash_monitor.workbench.model import load_model
import shared_cache                                             # test/: built by one process, the others wait

SEEDS = [0, 1, 2]          # a small ensemble keeps the tests fast; diagnose is given the same
WIDTH_M = 0.005
FRICTION = {"effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": 2.0}


@pytest.fixture(scope="module")
def model():
    return load_model(None, width_m=WIDTH_M)


@pytest.fixture(scope="module")
def ref(model):
    """The default model's reference at 5 mm as the watch uses it (6 seeds, a 4 s build recording, a 2.5 % width
    grid; from the cache, built there once: ~30 s), loaded from its file."""
    return reference.load(shared_cache.watch_reference(model).path)


def _diagnose_before(meas, model, seeds=None):
    run = diagnose.prepare(meas, model, seeds)
    diagnose.screen_step(run)
    return run.before


@pytest.fixture(scope="module")
def built_on_a_recording(model):
    """(recording, reference built on it without record-mean seeds): a 3 s drive whose load mass is 15 % heavier than
    the model's, built once for the two tests below (a build runs diagnose's consistency test: ~12 s)."""
    meas = synthetic.hidden_effect_recording(model, 3.0, seed=36, config_overrides={
        "effects.load_mass_drift": True, "load_mass_drift.relative_change": 0.15})
    return meas, reference.build(model, seeds=SEEDS, width_step=0.2, recording=meas, record_mean_seeds=0)


@pytest.mark.slow
def test_a_reference_built_on_a_recording_is_diagnoses_test_on_it_to_the_last_digit(built_on_a_recording, tmp_path):
    """Built on the recording itself (its conditions, its noise floor, its number of events), saved and loaded,
    the reference's evaluation at the nominal width is diagnose's consistency test on it (the one screen_step ran
    while building: the reference keeps it as provenance): every view's T^2 and the residual to 1e-9 -- the views
    are rebuilt from the stored arrays by consistency.py's own functions, nothing re-implemented."""
    meas, built = built_on_a_recording
    own = reference.load(built.save(tmp_path / "own.watch.npz"))
    ours = own.evaluate(reference.evidence_from_measurement(meas, own), profile_width=False)
    theirs = own.meta["build_consistency"]
    assert own.meta["build_events_measured"] == ours.n_events
    assert ours.consistent == theirs["consistent"]
    for name, v in theirs["views"].items():
        assert ours.result.views[name].t2 == pytest.approx(v["T2"], rel=1e-9), name
        assert ours.result.views[name].dimension == v["dimension"]
    assert ours.result.residual_over_noise == pytest.approx(theirs["residual_over_noise"], rel=1e-9)


@pytest.mark.slow
def test_the_record_mean_seeds_sharpen_the_record_means_noise_and_nothing_else(model, built_on_a_recording, tmp_path):
    """More noise seeds of the model at its nominal width (reference.RECORD_MEAN_SEEDS) give the record mean's floor
    and whitening more degrees of freedom (K x (DC_BLOCKS - 1) -> (K + extra) x (DC_BLOCKS - 1)); the other views
    are untouched (to rounding: 1e-12). A reference of format 3 (none) is still read, with diagnose's estimate."""
    import numpy as np
    meas, plain = built_on_a_recording
    more = reference.load(reference.build(model, seeds=SEEDS, width_step=0.2, recording=meas, record_mean_seeds=9)
                          .save(tmp_path / "more.watch.npz"))
    assert plain.view_dof()["record_mean"] == 3 * 3 and more.view_dof()["record_mean"] == (3 + 9) * 3
    assert len(more.record_mean_dc) == 9 and all(d.shape[1] == len(more.dc_names) for d in more.record_mean_dc)
    evidence = reference.evidence_from_measurement(meas, plain)
    a, b = plain.evaluate(evidence, profile_width=False), more.evaluate(evidence, profile_width=False)
    for name, v in a.result.views.items():
        if name != "record_mean":
            assert b.result.views[name].t2 == pytest.approx(v.t2, rel=1e-12), name
    assert b.result.views["record_mean"].t2 != a.result.views["record_mean"].t2
    # format 3: no record-mean seeds in the file
    path = plain.save(tmp_path / "v3.watch.npz")
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files if not k.startswith("record_mean_dc")}
    arrays["format_version"] = np.array(3)
    np.savez(tmp_path / "v3.watch.npz", **arrays)
    old = reference.load(tmp_path / "v3.watch.npz")
    assert old.record_mean_dc == [] and old.view_dof()["record_mean"] == 3 * 3
    assert old.evaluate(evidence, profile_width=False).result.views["record_mean"].t2 == \
        a.result.views["record_mean"].t2


@pytest.mark.slow
@pytest.mark.parametrize("label,overrides,consistent", [("clean", {}, True), ("friction 2 N*m", FRICTION, False)])
def test_the_models_own_reference_gives_diagnoses_verdict(model, ref, label, overrides, consistent):
    """Built on the model's own recording (the watch's reference), on another recording: the verdict and the views
    outside their band are diagnose's. The T^2 themselves are not equal: the two ensembles run under other conditions
    (the pulse phase), and the views' whitening is estimated from K x E model events (with 3 seeds x 12 events a
    clean recording's T^2 were 5.5 vs 9.4 with the limit at 20.1, 2 N*m of friction 526 vs 1314; with 6 x 16, 1 N*m
    227 vs 221: docs/model_watch.md)."""
    meas = synthetic.hidden_effect_recording(model, 4.0, seed=41, config_overrides=overrides)
    ours = ref.evaluate(reference.evidence_from_measurement(meas, ref), profile_width=False)
    theirs = _diagnose_before(meas, model)
    assert ours.consistent == theirs.consistent == consistent, label
    outside = {n for n, v in ours.result.views.items() if v.outside_band}
    assert outside == {n for n, v in theirs.views.items() if v.outside_band}, label
    ev, dv = ours.result.views["event_average"], theirs.views["event_average"]
    assert ev.dimension == dv.dimension
    if not consistent:       # both far outside the band (the effect's T^2 is ~25x and ~65x the limit here)
        assert min(ev.t2, dv.t2) > 5 * ev.limit, (ev.t2, dv.t2)
    assert abs(ours.result.residual_over_noise - theirs.residual_over_noise) \
        < 0.25 * max(theirs.residual_over_noise, 1.0)


def test_a_worn_clutch_is_the_measurand_not_a_model_error(model, ref):
    """A drive whose width grew by 16 % (5.0 -> 5.8 mm) fails the test at the model's nominal width; the watch
    compares at the width that fits (the measurand): consistent, at the true width within 0.15 mm (one 4 s
    recording's width scatters by ~0.1 mm)."""
    meas = synthetic.hidden_effect_recording(model, 4.0, seed=33, scenario={"width_m": 0.0058})
    ev = reference.evidence_from_measurement(meas, ref)
    assert not ref.evaluate(ev, profile_width=False).consistent
    prof = ref.evaluate(ev)
    assert prof.consistent
    assert abs(prof.width_m - 0.0058) < 1.5e-4


def _without_local_whitening(monkeypatch, ref):
    monkeypatch.setattr(reference.WindowReference, "local_views", lambda self, g: self.views)
    for v in ref._windows.values():
        v._local = {}


@pytest.mark.parametrize("label,overrides,exceeds", [
    ("clean", {}, False),
    ("friction 1 N*m", {"effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": 1.0}, True)])
def test_a_drive_far_from_the_nominal_width_is_whitened_by_the_models_events_at_its_width(model, ref, monkeypatch,
                                                                                        label, overrides, exceeds):
    """A drive at +30 % of the model's width (6.5 mm on the 5 mm model): the model's own noise there is not its noise
    at 5 mm (the far-side impact moves), so the test whitens by the model's events at the grid width the drive sits
    at. The alarm rule as the watch applies it (robust: the window exceeds, and so does every leave-one-out window):
    a clean drive does not exceed it and 1 N*m of wheel friction does; whitened at the nominal width the friction's
    event-average T^2 is several times smaller (measured: 38.7 against 215, below the rule's 42.7). Seed 61 is a
    heavy clean window (measured: event-average T^2 43.4 local, 79.6 nominal-whitened, which also exceeded robustly;
    seeds 62-66: 5-10 local)."""
    from backlash_monitor.watch.alarm import AlarmRule
    rule = AlarmRule().check()
    wide = load_model(None, width_m=1.3 * WIDTH_M)
    meas = synthetic.hidden_effect_recording(wide, 4.0, seed=61, config_overrides=overrides)
    for s in ("omega1", "omega2"):
        meas.signals.pop(s)                         # the live watch's signals
    ev = reference.evidence_from_measurement(meas, ref, last_n=16, significant_noise=True)
    local = ref.evaluate(ev, where=False)
    assert abs(local.width_m - 1.3 * WIDTH_M) < 4e-4
    robust = rule.exceeds(local)[0] and all(rule.result_exceeds(r)[0] for r in ref.leave_one_out(ev, local))
    assert robust == exceeds, (label, {n: v.t2 for n, v in local.result.views.items()})
    if exceeds:
        _without_local_whitening(monkeypatch, ref)
        nominal = ref.evaluate(ev, where=False)
        assert local.result.views["event_average"].t2 > 2 * nominal.result.views["event_average"].t2


def test_a_reference_file_of_another_format_is_refused_naming_the_rebuild(ref, tmp_path):
    import json
    with np.load(ref.path) as z:
        data = {k: z[k] for k in z.files}
    data["format_version"] = np.array(reference.FORMAT_VERSION + 1)
    bad = tmp_path / "old.watch.npz"
    np.savez(bad, **data)
    with pytest.raises(reference.ReferenceError, match="format version .*watch-reference"):
        reference.load(bad)
    with pytest.raises(reference.ReferenceError, match="does not exist"):
        reference.load(tmp_path / "none.watch.npz")
    assert json.loads(str(data["meta"]))["model_label"] == ref.model_label


def test_sample_ring_keeps_the_last_samples_across_its_wrap():
    ring = SampleRing(("x",), 10)
    ring.append(0, {"x": np.arange(7.0)})
    ring.append(7, {"x": np.arange(7.0, 16.0)})
    assert (ring.start, ring.end) == (6, 16)
    assert np.array_equal(ring.get("x", 6, 16), np.arange(6.0, 16.0))
    with pytest.raises(IndexError):
        ring.get("x", 5, 8)
    ring.append(30, {"x": np.ones(3)})         # a gap: what came before is not this stream's
    assert (ring.start, ring.end) == (30, 33)


def test_sample_ring_returns_exactly_the_samples_it_was_given():
    rng = np.random.default_rng(1)
    ring, held, k = SampleRing(("x",), 97), [], 0
    for _ in range(300):
        n = int(rng.integers(1, 150))
        x = rng.standard_normal(n)
        ring.append(k, {"x": x})
        held.extend(x)
        k += n
        lo = int(rng.integers(ring.start, ring.end))
        hi = int(rng.integers(lo, ring.end + 1))
        assert np.array_equal(ring.get("x", lo, hi), np.array(held[lo:hi])), (lo, hi)


STREAMS = ("a1", "a2", "angle_difference", "omega1")


@pytest.mark.parametrize("dc_names", [DC_SIGNALS, SEGMENT_SIGNALS])
def test_live_events_are_the_workbench_events_in_any_chunking(model, dc_names):
    """Fed in chunks of 777 or 5000 samples, the live events are diagnose's events (events.event_set): the same
    entries and segments, and the period means (a1, a2 and, streamed, the motor speed omega1) to the few samples
    the period estimates differ by."""
    meas = synthetic.hidden_effect_recording(model, 3.0, seed=33)
    ref_ev = event_set(meas.signals, meas.sample_period_s, dc_names)
    for chunk in (777, 5000):
        live = LiveEvents(meas.sample_period_s, 12500, dc_names=dc_names)
        got = []
        n = meas.n_samples
        for k in range(0, n, chunk):
            got += live.feed(k, *(meas.signals[s][k:k + chunk] for s in STREAMS))
        entries = [e.entry_sample_index for e in got]
        assert entries == list(ref_ev.entries[:len(entries)]) and len(entries) >= ref_ev.n_events - 1
        for i, e in enumerate(got):
            assert np.array_equal(e.raw, ref_ev.raw[i])
            # the period mean: over the median of the last 16 onset spacings (live) or of the whole record's
            # (offline): the periods differ by up to ~10 samples (the trigger's scatter), the accelerations' means
            # by < 0.03 m/s^2, the motor speed's (~0.1 % of it in a period's ripple) by < 0.05 rad/s
            assert e.dc.shape == (len(dc_names),)
            assert np.allclose(e.dc[:2], ref_ev.dc[i, :2], rtol=0, atol=0.03)
            assert np.allclose(e.dc[2:], ref_ev.dc[i, 2:], rtol=0, atol=0.05)


def test_a_watch_with_the_motor_speed_needs_it_in_every_feed(model, ref):
    live = LiveEvents(2e-5, 12500, dc_names=DC_SIGNALS)
    with pytest.raises(ValueError, match="omega1"):
        live.feed(0, np.zeros(100), np.zeros(100), np.zeros(100))
    with pytest.raises(ValueError, match="record-mean signals"):
        LiveEvents(2e-5, 12500, dc_names=("a1", "omega2"))
    watch = ModelWatch(ref, window_events=16, record_mean=SEGMENT_SIGNALS)     # a drive without omega1
    assert watch.feed(0, np.zeros(100), np.zeros(100), np.zeros(100)) == []


def test_the_window_evidence_stacks_its_raw_segments_only_when_read(model, ref):
    """The watch's evidence reads the events' raw segments only when asked (where, leave-one-out): the same
    segments, and the same evaluation as an Evidence holding them."""
    events = _events(model, 5.0, 37)[:16]
    watch = ModelWatch(ref, window_events=16)
    for e in events:
        watch.add_event(e)
    ev = watch.evidence()
    assert ev._raw is None and ev.n_events == 16
    assert np.array_equal(ev.raw, np.stack([e.raw for e in events]))
    plain = reference.Evidence(ev.raw, ev.dc, ev.spec, ev.noise_psd, ev.entries, ev.dc_names, ev.denoised,
                               ev.quant_step)
    x, y = ref.evaluate(ev, clip_p=1e-3), ref.evaluate(plain, clip_p=1e-3)
    assert {n: v.t2 for n, v in x.result.views.items()} == {n: v.t2 for n, v in y.result.views.items()}
    assert x.where == y.where


def test_the_evaluations_shortcuts_compute_what_they_replace(model, ref):
    """The events' measured vectors written in place are the weighted segments, features and means side by side;
    consistency.test given the events' coordinates (evaluate projects them once, for the clipping weights) is the
    test projecting them itself -- on a window with an odd event, so that the clipping acts."""
    from backlash_monitor.workbench import consistency
    events = _events(model, 5.0, 37)[:16]
    events[7].raw = events[7].raw * 2.0
    events[7].denoised = events[7].denoised * 2.0
    watch = ModelWatch(ref, window_events=16)
    for e in events:
        watch.add_event(e)
    ev = watch.evidence()
    window = ref.for_window(ev.noise_psd, ev.n_events, ev.dc_names, ev.quant_step)
    views = window.views
    targets = window.event_targets(ev)
    assert np.array_equal(targets, np.hstack([(ev.denoised * window.w[None, :, None]).reshape(16, -1),
                                              ev.spec * window.ws[None], ev.dc * window.wdc[None]]))
    assert np.allclose(targets.mean(axis=0), window.target(ev), rtol=1e-12, atol=1e-12)
    residuals = targets - window.base[None]
    radius = ref.clip_radius(views, 1e-3)
    sl = dict(views.blocks)["event_average"]
    coords = residuals @ views.basis[:, sl]
    assert consistency.clipped_mean(coords, radius["event_average"])[1].min() < 1.0       # the odd event is clipped
    r = window.target(ev) - window.base
    own = consistency.test(views, r, event_residuals=residuals, clip_radius=radius)
    given = consistency.test(views, r, event_residuals=residuals, clip_radius=radius,
                             event_coords={"event_average": coords})
    assert {n: v.t2 for n, v in own.views.items()} == {n: v.t2 for n, v in given.views.items()}
    assert own.residual_over_noise == given.residual_over_noise


def test_alarm_state_persistence_and_clearing():
    state = AlarmState(AlarmRule(view_p=1e-6, residual_ratio=3.0, persistence=3, clear_after=4))
    seq = [True, True, False, True, True, True, False, True, False, False, False, False]
    levels = []
    for i, x in enumerate(seq):
        state.update(x, i)
        levels.append(state.level)
    # two exceeding then one not: no WARN; three in a row: WARN since the first of them (3)
    assert levels[:5] == ["OK"] * 5 and levels[5] == "WARN"
    assert state.since == 8 or levels[5] == "WARN"
    # OK again only after 4 consecutive evaluations that do not exceed (8..11)
    assert levels[6:11] == ["WARN"] * 5 and levels[11] == "OK"
    with pytest.raises(ValueError, match="persistence"):
        AlarmRule(persistence=0).check()


def _events(model, seconds, seed, overrides=None):
    meas = synthetic.hidden_effect_recording(model, seconds, seed=seed, config_overrides=overrides)
    live = LiveEvents(meas.sample_period_s, ref_period := 12500, dc_names=DC_SIGNALS)
    out = []
    for k in range(0, meas.n_samples, 5000):
        out += live.feed(k, *(meas.signals[s][k:k + 5000] for s in STREAMS))
    assert ref_period == 12500
    return out


def test_one_odd_event_does_not_raise_the_alarm_but_an_effect_does(model, ref):
    """A window in which one event is odd (its a1 and a2 doubled): taken as it is (the plain mean, diagnose's) it
    exceeds the rule; the watch's bounded-influence event average does not. A window of events with 2.5 N*m of
    friction goes WARN."""
    rule = AlarmRule(view_p=1e-6, residual_ratio=3.0, persistence=1)
    dof = ref.view_dof()
    clean = _events(model, 5.0, 37)[:16]
    clean[7].raw = clean[7].raw * 2.0
    clean[7].denoised = clean[7].denoised * 2.0
    watch = ModelWatch(ref, window_events=16, rule=rule)
    u = [watch.add_event(e) for e in clean][-1]
    plain = ref.evaluate(watch.evidence(), where=False)
    assert rule.exceeds(plain, dof)[0]
    assert not rule.exceeds(u.evaluation, dof)[0] and not u.exceeding and u.level == "OK"
    friction = _events(model, 5.0, 38, FRICTION | {"wheel_coulomb_friction.torque_Nm": 2.5})[:16]
    watch = ModelWatch(ref, window_events=16, rule=rule)
    u = [watch.add_event(e) for e in friction][-1]
    assert u.exceeding and u.level == "WARN"


def test_the_watch_stays_ok_on_its_model_and_warns_when_an_effect_switches_on(model, ref):
    """A 5 mm drive on its model for 8 s, then 2 N*m of wheel friction switched on at run time
    (PlantSimulator.set_parameters): OK before, WARN within 16 onsets after, the WARN's evaluations outside the
    band in the event average."""
    cfg = model.plant_config({"effects.wheel_coulomb_friction": True})      # neutral until switched
    sim = PlantSimulator([Scenario(width_m=WIDTH_M, seed=5)], config=cfg,
                         outputs=("a1", "a2", "angle_difference", "omega1"))
    watch = ModelWatch(ref, window_events=12, rule=AlarmRule(view_p=1e-6, residual_ratio=3.0, persistence=2))
    switch = 8 * 50_000
    updates = []
    for k in range(0, 16 * 50_000, 2500):
        if k == switch:
            sim.set_parameters({"wheel_coulomb_friction.torque_Nm": 2.0})
        ch = sim.run(2500)
        updates += watch.feed(ch.first_sample_index, ch.a1[0], ch.a2[0], ch.angle_difference[0], ch.omega1[0])
    before = [u for u in updates if u.entry_sample_index < switch]
    after = [u for u in updates if u.entry_sample_index >= switch]
    assert before and all(u.level == "OK" for u in before)
    first = next(i for i, u in enumerate(after) if u.level == "WARN")
    assert first + 1 <= 16
    warn = after[first]
    assert "event_average" in warn.exceeding_views or "residual" in warn.exceeding_views
    assert warn.where[0] in ("before_entry", "gap_traversal", "impact", "settling")


def test_a_recordings_model_fit_as_analyze_shows_it(model, ref):
    clean = synthetic.hidden_effect_recording(model, 3.0, seed=34)
    fit = evaluate_recording(clean, ref)
    assert fit["level"] == "OK" and fit["events"] >= 10 and fit["model"] == ref.model_label
    bad = synthetic.hidden_effect_recording(model, 3.0, seed=35, config_overrides=plant_adapter.config_overrides(
        {"wheel_coulomb_friction.torque_Nm": 2.5}))
    assert evaluate_recording(bad, ref)["level"] == "WARN"


def test_the_live_watch_quantises_the_model_at_the_adcs_step_as_diagnose_does(model, ref):
    """A drive behind an ADC (a2 rounded to a 16-bit step over +-4 g, no other noise): the live watch finds the step
    once on the first window, its noise floor is the white noise before the quantiser (analysis.sensor_noise_floor:
    none here) and its views quantise the model's events at that step -- the evaluation is the reference's on the
    same events with diagnose's estimate of the chain (evidence_from_measurement: the step read off the whole
    record), to rounding; and the spectral shape stays inside its band, where a white step^2/12 floor put it far
    out (docs/model_watch.md, Limits)."""
    from backlash_monitor.workbench.analysis import quantisation_step
    step = 2 * 4 * 9.81 / 2 ** 16
    meas = synthetic.hidden_effect_recording(model, 4.6, seed=44)
    meas.signals["a2"] = np.round(meas.signals["a2"] / step) * step
    sig = {s: meas.signals[s] for s in STREAMS}
    watch = ModelWatch(ref)
    updates = []
    for k in range(0, meas.n_samples, 5000):
        updates += watch.feed(k, *(sig[s][k:k + 5000] for s in STREAMS))
    assert len(watch.events) == watch.window_events and updates
    window = np.concatenate([e.raw[1] for e in watch.events])
    assert quantisation_step(window) == pytest.approx(step, rel=1e-6)
    assert watch.quantisation()[1] == pytest.approx(step, rel=1e-6) and watch.quantisation()[0] == 0.0
    ev = updates[-1].evaluation
    assert np.all(ev.noise_psd == 0.0)
    psd = dict(zip(("a1", "a2"), np.mean([e.psd for e in watch.events if e.psd is not None], axis=0)))
    assert np.allclose(watch.noise_floor(), ref.noise_floor(psd, significant=True, quant_step=watch.quantisation()))
    offline = reference.evidence_from_measurement(meas, ref, last_n=watch.window_events, significant_noise=True)
    assert offline.quant_step[1] == pytest.approx(step, rel=1e-6)
    live = watch.evidence()
    assert np.array_equal(live.quant_step, offline.quant_step)
    same = reference.Evidence(live.raw, live.dc, live.spec, offline.noise_psd, live.entries, live.dc_names,
                              quant_step=offline.quant_step)
    a = ref.evaluate(same, where=False, clip_p=watch.rule.event_clip_p).result.views
    for name, v in ev.result.views.items():
        assert v.t2 == pytest.approx(a[name].t2, rel=1e-9), name
    spectral_view = ev.result.views["spectral_shape"]
    assert not spectral_view.outside_band, spectral_view.t2
    white = ref.evaluate(reference.Evidence(live.raw, live.dc, live.spec, np.array([0.0, step ** 2 / 6 * 2e-5]),
                                            live.entries, live.dc_names), where=False)
    assert white.result.views["spectral_shape"].t2 > 3 * spectral_view.limit, white.result.views["spectral_shape"].t2


@pytest.mark.slow
def test_the_motor_speed_shows_a_load_on_the_motor_that_the_accelerations_do_not(model, ref):
    """0.25 p.u. more load on the induction motor slows it by its slip (~2 rad/s) and leaves the accelerations'
    period means at ~0: the live watch with omega1 in its record mean sees it outside the view's band (as diagnose
    does on a recording with omega1), the watch on a1 and a2 alone sees nothing; the clean drive is inside both."""
    load = plant_adapter.config_overrides({"motor_load_offset.load_pu": 0.25})
    for overrides, outside_with_omega1 in ((None, False), (load, True)):
        meas = synthetic.hidden_effect_recording(model, 5.0, seed=51, config_overrides=overrides)
        views = {}
        for record_mean in (DC_SIGNALS, SEGMENT_SIGNALS):
            watch = ModelWatch(ref, window_events=16, record_mean=record_mean)
            updates = []
            for k in range(0, meas.n_samples, 5000):
                updates += watch.feed(k, *(meas.signals[s][k:k + 5000] for s in STREAMS))
            views[len(record_mean)] = updates[-1].evaluation.result.views["record_mean"]
        assert views[3].dimension == 3 and views[2].dimension == 2
        assert views[3].outside_band == outside_with_omega1
        assert not views[2].outside_band
        if outside_with_omega1:
            assert views[3].t2 > 20 * views[2].t2
