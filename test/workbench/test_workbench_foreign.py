"""The workbench on drives our simulator did not make (issue 20): recordings of foreign_drives/ -- an independent
implementation of the drive's physics with effects in other laws and other sensor chains (docs/foreign_drives.md).
No inverse crime: every inference here is tested on data our model did not make.

3 s recordings (12 onset events), seeds 300-309 (the bench's foreign suite uses 5000+, foreign_drives' own tests
100-199). Each diagnosis runs the whole catalogue (~15-70 CPU-s), on the ensemble ENSEMBLE gives it."""
import os

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from foreign_drives.drive import make_recording                       # noqa: E402
from foreign_drives.spec import EffectSpec as E                       # noqa: E402
from foreign_drives.spec import RecordingSpec, SensorNuisance         # noqa: E402

from backlash_monitor.workbench.diagnose import diagnose              # noqa: E402
from backlash_monitor.workbench.measurement import Measurement        # noqa: E402
from backlash_monitor.workbench.model import load_model               # noqa: E402

DURATION_S = 3.0
MEMS_ADC = SensorNuisance(a1_noise_rms_m_s2=0.05, a2_noise_rms_m_s2=0.01, a1_lsb_m_s2=0.015, a2_lsb_m_s2=0.0012)


def _spec(label, kind, seed, effects=(), width=0.0075, eta=0.025, n1=0.89, sensor=SensorNuisance(), **more):
    return RecordingSpec(label=label, kind=kind, width_m=width, eta_k=eta, n1=n1, effects=tuple(effects),
                         sensor=sensor, seed=seed, duration_s=DURATION_S, **more).check()


SPECS = {
    "clean_mems": _spec("clean_mems", "clean", 300, width=0.0045, eta=0.04, n1=0.95, sensor=MEMS_ADC),
    "friction_tanh": _spec("friction_tanh", "one", 301,
                           [E("wheel_friction_tanh", {"torque_Nm": 1.4, "smoothing_speed_rad_s": 15.0})]),
    "butterworth2_a1": _spec("butterworth2_a1", "one", 302,
                             [E("lowpass_butterworth", {"signal": "a1", "order": 2, "corner_hz": 700.0})]),
    "vibration_131Hz": _spec("vibration_131Hz", "outside", 303,
                             [E("structural_vibration", {"amplitude_pu": 0.4, "frequency_hz": 131.0,
                                                         "phase_rad": 0.2})]),
    "width_6_to_7": _spec("width_6_to_7", "one", 304, [E("drift_width", {"change": 0.001})], width=0.006),
    "friction_tanh_strong": _spec("friction_tanh_strong", "one", 306,
                                  [E("wheel_friction_tanh", {"torque_Nm": 2.5, "smoothing_speed_rad_s": 15.0})]),
    "supply_sag": _spec("supply_sag", "one", 307, [E("supply_voltage", {"relative_change": -0.15})],
                        width=0.006, eta=0.03, n1=0.91),
    "hot_rotor": _spec("hot_rotor", "one", 308, [E("motor_rotor_resistance", {"relative_change": 0.45})],
                       width=0.0085, eta=0.0175, n1=0.93),
    # cut from a running drive 31 ms into a pulse (the pulse began before sample 0, as in a watch's snapshot)
    "mass_in_pulse": _spec("mass_in_pulse", "one", 309, [E("drift_mass", {"relative_change": 0.3})],
                           pulse_first_s=0.2192),
    "offset_a2": _spec("offset_a2", "one", 305, [E("bias_constant", {"signal": "a2", "bias_m_s2": 2.0})], width=0.009),
    # issue 31: a width change together with another effect
    "width_plus_offset": _spec("width_plus_offset", "two", 310, [E("drift_width", {"change": 0.001}),
                                                                 E("bias_constant", {"signal": "a2", "bias_m_s2": 1.5})],
                               width=0.006),
}
# The model's noise ensemble of a diagnosis: diagnose's default (analysis.DEFAULT_SEEDS, 6 seeds), or 3 seeds for the
# recordings on which the test's claim was measured to hold with margin at 3 as well (29 Nov; the diagnosis 20-35 %
# less CPU): clean_mems consistent, a2 noise 0.0099 m/s^2 (0.01 +- 25 %); friction_tanh a discovery naming the wheel
# Coulomb friction; supply_sag supply_voltage_drift; hot_rotor rotor_resistance_drift at +0.413 +- 0.022 (the bound
# 0.45 +- 0.107); vibration_131Hz nothing_explains, a line at 131.3 Hz not locked; offset_a2 accelerometer_bias[a2]
# 1.998 m/s^2 (2.0 +- 0.2). Not on the others: at 3 seeds butterworth2_a1 was a partial, friction_tanh_strong did not
# name the Coulomb friction, mass_in_pulse named the a2 gain without the mass, width_6_to_7 measured 6.77 mm (7 +- 0.2).
THREE_SEEDS = [0, 1, 2]
ENSEMBLE = {name: THREE_SEEDS for name in ("clean_mems", "friction_tanh", "supply_sag", "hot_rotor", "vibration_131Hz",
                                           "offset_a2")}
_CACHE: dict = {}


def diagnosed(name):
    """(diagnosis JSON, truth) of one foreign recording, diagnosed against the model at its user's nominal values
    (with the ensemble ENSEMBLE gives it)."""
    if name not in _CACHE:
        spec = SPECS[name]
        rec = make_recording(spec)
        meas = Measurement(f"foreign:{name}", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
        model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)
        _CACHE[name] = (diagnose(meas, model, seeds=ENSEMBLE.get(name), propose=False).to_json(), rec.truth)
    return _CACHE[name]


def _named(d) -> set:
    out = set()
    for entry in (d["discovery_parameters"], d["second_effect"]):
        if entry:
            out |= {entry["effect"]} | {c.split("[")[0] for c in entry["indistinguishable_from"]}
    return out


@pytest.mark.slow
def test_a_clean_foreign_drive_behind_a_noisy_quantised_sensor_is_consistent():
    """No effect, but a MEMS-like sensor chain (white noise after the sensor, a 16-bit ADC): not a discovery --
    the sensor's noise floor is a nuisance the spectral views allow for, estimated from the recording."""
    d, _ = diagnosed("clean_mems")
    assert d["verdict"] == "consistent" and d["discovery"] is None, d["message"]
    assert d["additions"] == []
    # the a2 chain comes back from the recording: 0.01 m/s^2 of white noise before an ADC of step 0.0012 m/s^2 (its
    # step^2/12 is in the noise band too, and is not counted as the white noise's)
    assert d["sensor_noise_floor"]["rms_m_s2"]["a2"] == pytest.approx(0.01, rel=0.25)
    assert d["sensor_noise_floor"]["quantisation_step_m_s2"]["a2"] == pytest.approx(0.0012, rel=1e-6)


@pytest.mark.slow
def test_a_foreign_friction_law_is_named_in_its_family():
    """A smooth (tanh) wheel friction of 1.4 N*m -- not the catalogue's law -- is named as wheel friction, or as
    one of its rim-force twins with the friction flagged as indistinguishable (at one rotation direction a wheel
    torque T acts like a force T/r on the rim)."""
    d, truth = diagnosed("friction_tanh")
    assert d["verdict"] == "discovery", d["message"]
    assert set(truth.families) <= _named(d), (truth.families, d["message"])
    assert [a["role"] for a in d["additions"]][0] == "discovery"


@pytest.mark.slow
def test_a_strong_foreign_friction_is_named_although_its_linearisation_misses_it():
    """2.5 N*m of smooth wheel friction: the other laws of the wheel's torque balance fit it as well (the wheel
    never reverses), but at this strength the candidates' linearisation at the nominal model misses the Coulomb law
    (screened, never refined, so never compared). Refining the best one's balance siblings names it: as the
    discovery or flagged indistinguishable from it."""
    d, truth = diagnosed("friction_tanh_strong")
    assert d["verdict"] == "discovery", d["message"]
    assert set(truth.families) <= _named(d), (truth.families, d["message"])
    refined = {r["effect"] for r in d["ranked"] if not r.get("screening_only")}
    assert "wheel_coulomb_friction" in refined


@pytest.mark.slow
def test_a_weaker_motor_is_never_called_a_motor_load_without_saying_it_may_be_the_motor():
    """A supply voltage 15 % low slows the motor like a load or a friction on its shaft. The diagnosis names the
    weaker motor (supply_voltage_drift, or its twin rotor_resistance_drift), or, if it names a motor-side torque,
    says that a weaker motor looks the same on this recording and what measurement separates them."""
    d, _ = diagnosed("supply_sag")
    assert d["verdict"] == "discovery", d["message"]
    named = _named(d)
    if not named & {"supply_voltage_drift", "rotor_resistance_drift"}:
        assert d["discovery"] in ("motor_coulomb_friction", "motor_load_offset"), d["message"]
        assert "supply voltage" in d["message"] and "stator current" in d["message"], d["message"]
