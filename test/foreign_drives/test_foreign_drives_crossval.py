"""Cross-validation: the foreign generator (foreign_drives/, written independently) against the project's
simulator (backlash_monitor.plant). Two implementations of SPEC section 3 agreeing is the point.

Measured (docs/foreign_drives.md "Agreement with our simulator"): noise-free, with the project's run-in at
16 s (its periodic state), the two agree to 9e-7 of a1's peak, 6e-7 of a2's, 1e-8 rad in the angle difference
and 4e-6 rad/s in the speeds; with noise, the event-averaged onset windows of the two differ as little as two
groups of the project's own seeds differ from each other.
"""
import numpy as np
import pytest

from backlash_monitor.plant import Scenario, load_plant_config, simulate_batch
from backlash_monitor.plant.effects import CATALOGUE_NAMES
from foreign_drives import constants as C
from foreign_drives.drive import make_recording
from foreign_drives.spec import EffectSpec as E
from foreign_drives.spec import RecordingSpec

WIDTHS = (0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01)
SPEC_IMPACT_MS = (14.7, 19.1, 22.9, 29.5, 33.1, 35.4)
PERIODIC_RUN_IN_S = 16.0     # the project's run-in long enough to reach the periodic state (see the docs)
SIGNALS = ("a1", "a2", "omega1", "omega2", "angle_difference")


def onset_windows(d, x, beta, window=C.WINDOW_SAMPLES):
    inside = np.abs(d) < beta
    ks = np.flatnonzero(inside[1:] & ~inside[:-1]) + 1
    wins, imps = [], []
    for k in ks:
        if d[k - 1] > 0 and k + window <= len(d):
            wins.append(x[k:k + window])
            imps.append(np.flatnonzero(d[k:k + window] <= -beta)[0] * C.SAMPLE_PERIOD_S * 1e3)
    return wins, imps


def foreign(width, eta=0.025, n1=0.89, effects=(), seed=0, duration=1.0, noise=False, kind=None):
    kind = kind or ("clean" if not effects else "one")
    return make_recording(RecordingSpec("x", kind, width, eta, n1, effects=tuple(effects), seed=seed,
                                        duration_s=duration, noise=noise))


@pytest.fixture(scope="module")
def ours_clean():
    cfg = load_plant_config(overrides={"simulation.run_in_s": PERIODIC_RUN_IN_S})
    return simulate_batch([Scenario(w, 0.025, 0.89) for w in WIDTHS], duration_s=1.0, config=cfg, noise=False)


def test_noise_free_impact_times_and_waveforms_agree(ours_clean):
    for i, w in enumerate(WIDTHS):
        f = foreign(w)
        beta = w / C.WHEEL_RADIUS_M
        _, imp_f = onset_windows(f.signals["angle_difference"], f.signals["a1"], beta)
        _, imp_o = onset_windows(ours_clean.angle_difference[i], ours_clean.a1[i], beta)
        assert len(imp_f) == len(imp_o) == 4
        np.testing.assert_allclose(imp_f, imp_o, atol=0.02 + 1e-9)             # within one sample
        assert np.mean(imp_f) == pytest.approx(SPEC_IMPACT_MS[i], abs=0.06)      # SPEC's figures, 0.1 ms rounding
        assert [k for k, _ in f.true_entries()] == [k for k, _ in ours_clean.entries[i]]
        for name in SIGNALS:
            a, b = f.signals[name], getattr(ours_clean, name)[i]
            tol = {"a1": 2e-5 * np.max(np.abs(b)), "a2": 2e-5 * np.max(np.abs(b)), "omega1": 1e-4,
                   "omega2": 1e-4, "angle_difference": 1e-7}[name]
            assert np.max(np.abs(a - b)) < tol, (w, name, np.max(np.abs(a - b)))


CORNERS = [(0.0125, 0.97), (0.05, 0.89), (0.05, 0.97)]


@pytest.fixture(scope="module")
def ours_corners():
    """The grid corners in one batch (the scenarios are independent: each one's run is the one it has alone)."""
    cfg = load_plant_config(overrides={"simulation.run_in_s": PERIODIC_RUN_IN_S})
    return simulate_batch([Scenario(0.0075, eta, n1) for eta, n1 in CORNERS], duration_s=0.5, config=cfg,
                          noise=False)


@pytest.mark.parametrize("eta,n1", CORNERS)
def test_noise_free_grid_corners_agree(eta, n1, ours_corners):
    f = foreign(0.0075, eta, n1, duration=0.5)
    for name in ("a1", "a2"):
        b = getattr(ours_corners, name)[CORNERS.index((eta, n1))]
        assert np.max(np.abs(f.signals[name] - b)) < 2e-5 * np.max(np.abs(b)), name


# forms whose law coincides with a catalogue effect's: the two implementations of the same physics
SAME_PHYSICS = [
    (E("mass_force_constant", {"force_N": 11.0}), {"mass_force_offset.force_N": 11.0}),
    (E("wheel_load_torque", {"torque_Nm": 1.3}), {"wheel_coulomb_friction.torque_Nm": 1.3}),
    (E("motor_load_constant", {"torque_Nm": 1.6}), {"motor_load_offset.load_pu": 0.08}),
    (E("drift_width", {"change": 0.001}), {"backlash_width_drift.change": 0.001}),
    (E("drift_mass", {"relative_change": 0.3}), {"load_mass_drift.relative_change": 0.3}),
    (E("drift_wheel_inertia", {"relative_change": 0.35}), {"wheel_inertia_drift.relative_change": 0.35}),
    (E("drift_spring", {"relative_change": 0.5}), {"spring_stiffness_drift.relative_change": 0.5}),
    (E("drift_eta_k", {"relative_change": 0.6}), {"absorber_consistency_drift.relative_change": 0.6}),
    (E("drift_n1", {"change": 0.05}), {"absorber_flow_index_drift.change": 0.05}),
    (E("drift_working_resistance", {"relative_change": 0.4}), {"working_resistance_drift.relative_change": 0.4}),
    (E("drift_pulse_amplitude", {"relative_change": -0.15}), {"pulse_amplitude_drift.relative_change": -0.15}),
    (E("clutch_damping_value", {"relative_change": 0.6}), {"clutch_contact_damping.relative_change": 0.6}),
    (E("clutch_contact_asymmetric", {"drive_relative_change": -0.3, "far_relative_change": -0.3}),
     {"clutch_contact_stiffness.relative_change": -0.3}),
    (E("gain_constant", {"signal": "a2", "relative_change": 0.15}), {"accelerometer_gain.a2_relative_change": 0.15}),
    (E("bias_constant", {"signal": "a1", "bias_m_s2": -2.0}), {"accelerometer_bias.a1_m_s2": -2.0}),
]


@pytest.fixture(scope="module")
def ours_catalogue():
    """The project's simulator with its whole catalogue on (one kernel), one scenario per case."""
    cfg = load_plant_config(overrides={"simulation.run_in_s": PERIODIC_RUN_IN_S,
                                       **{f"effects.{n}": True for n in CATALOGUE_NAMES}})
    n = len(SAME_PHYSICS)
    params = {}
    for i, (_, ours) in enumerate(SAME_PHYSICS):
        for k, v in ours.items():
            params.setdefault(k, np.zeros(n))[i] = v
    return simulate_batch([Scenario(0.0075, 0.025, 0.89)] * n, duration_s=0.5, config=cfg, noise=False,
                          parameters=params)


@pytest.mark.parametrize("case", range(len(SAME_PHYSICS)), ids=[e.form for e, _ in SAME_PHYSICS])
def test_forms_with_a_catalogue_twin_agree_with_it(case, ours_catalogue):
    eff, _ = SAME_PHYSICS[case]
    f = foreign(0.0075, effects=[eff], duration=0.5)
    for name in ("a1", "a2", "angle_difference"):
        b = getattr(ours_catalogue, name)[case]
        scale = np.max(np.abs(b)) if name != "angle_difference" else 1.0
        tol = {"a1": 1e-4, "a2": 1e-4, "angle_difference": 1e-6}[name]
        assert np.max(np.abs(f.signals[name] - b)) < tol * scale, (eff.form, name, np.max(np.abs(f.signals[name] - b)))


def test_with_noise_the_event_statistics_agree():
    """Different noise realisations: compare distributions, with the onset events as the units (48 per side).
    The foreign event average must be as close to ours as two groups of our own seeds are to each other."""
    w = 0.005
    beta = w / C.WHEEL_RADIUS_M
    ours = simulate_batch([Scenario(w, 0.025, 0.89, seed=s) for s in range(12)], duration_s=2.0, noise=True)
    groups = []
    for half in (range(0, 6), range(6, 12)):
        wins, imps = [], []
        for i in half:
            x, t = onset_windows(ours.angle_difference[i], ours.a1[i], beta)
            wins += x
            imps += t
            assert [kd for _, kd in ours.entries[i]].count("onset") == 8
        groups.append((np.array(wins), np.array(imps)))
    wins, imps = [], []
    for s in range(170, 176):
        f = foreign(w, seed=s, duration=2.0, noise=True)
        kinds = [kd for _, kd in f.true_entries()]
        assert kinds.count("onset") == 8 and kinds.count("return") == 8       # 4 + 4 per second
        x, t = onset_windows(f.signals["angle_difference"], f.signals["a1"], beta)
        wins += x
        imps += t
    fw, fi = np.array(wins), np.array(imps)
    (oa, ia), (ob, ib) = groups
    assert len(fw) == len(oa) == len(ob) == 48
    se = np.sqrt(fi.var(ddof=1) / len(fi) + ia.var(ddof=1) / len(ia))
    assert abs(fi.mean() - ia.mean()) < 3 * se                               # far-side impact time
    assert 0.7 < fi.std() / ia.std() < 1.4                                    # its event-to-event spread
    rms = lambda x: float(np.sqrt(np.mean(x ** 2)))                          # noqa: E731
    assert rms(fw.mean(0) - oa.mean(0)) < 2.0 * rms(ob.mean(0) - oa.mean(0))  # event-averaged onset window of a1
    assert 0.8 < rms(fw - fw.mean(0)) / rms(oa - oa.mean(0)) < 1.25          # per-event spread about it
