"""A user's plug-in locked to a shaft's angle (issue 31): fitted as a sine/cosine pair with its phase lined up with
the recording. Before: screened at amplitude 0, where the phase has no derivative and the model's wheel angle does
not line up with the recording's; the amplitude went to its bound 0 (7e-20) and it explained 0 %.
The recording is made by foreign_drives (an independent implementation): a gear-mesh torque A*sin(alpha2 + phi)."""
import os
from pathlib import Path

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.plant.catalogue import builtin_catalogue          # noqa: E402
from backlash_monitor.workbench import fitting, plant_adapter           # noqa: E402
from backlash_monitor.workbench.model import load_model                  # noqa: E402

PLUGIN = Path(__file__).resolve().parents[2] / "docs" / "examples" / "wheel_angle_torque.py"
MY_EFFECTS = Path(__file__).resolve().parents[2] / "docs" / "examples" / "my_effects.py"


def test_a_term_naming_a_shaft_angle_with_a_phase_is_screened_as_a_sine_cosine_pair():
    cat = builtin_catalogue().with_files([PLUGIN, MY_EFFECTS])
    assert plant_adapter.angle_phase_index(cat["wheel_angle_torque"]) == 1
    assert plant_adapter.angle_phase_index(cat["torque_ripple"]) == 2          # alpha1, phase_rad
    assert plant_adapter.angle_phase_index(cat["wheel_drag"]) == -1            # no angle
    assert plant_adapter.angle_phase_index(cat["wheel_coulomb_friction"]) == -1
    model = load_model(None, effect_files=[PLUGIN])
    eff = plant_adapter.effect_by_name(model, "wheel_angle_torque")
    assert fitting.angle_pair(eff)
    pts = fitting.pair_points(eff)
    # one amplitude: stepped at the model's phase and a quarter turn on
    assert [i for i, _ in pts] == [0, 0]
    assert pts[0][1][0] > 0 and pts[1][1][0] == pts[0][1][0]
    assert pts[1][1][1] - pts[0][1][1] == pytest.approx(np.pi / 2)


def test_the_pair_estimate_recovers_amplitude_and_phase_of_a_sine_law():
    """On an exactly linear response (columns R0, R90 of a law A*sin(alpha + phi)): A and phi back."""
    model = load_model(None, effect_files=[PLUGIN])
    eff = plant_adapter.effect_by_name(model, "wheel_angle_torque")

    class P:                                  # the identity metric of a problem before its views are known
        views = None

        def project(self, r):
            return r

        def residual(self, pred):
            return self.target - pred

        def explained_share(self, a, b):
            return 1.0 - float(a @ a) / float(b @ b)

    rng = np.random.default_rng(3)
    r0, r90 = rng.normal(size=40), rng.normal(size=40)
    h = fitting._pair_steps(eff)
    a_true, phi_true = 2.9, 0.31
    prob = P()
    prob.target = (a_true / h[0]) * (np.cos(phi_true) * r0 + np.sin(phi_true) * r90)
    out = fitting.pair_estimate(prob, eff, np.stack([r0, r90], axis=1), h, np.zeros(40))
    assert out.x_lin[0] == pytest.approx(a_true, rel=1e-9)
    assert out.x_lin[1] == pytest.approx(phi_true, abs=1e-9)
    assert out.explained_lin == pytest.approx(1.0)


@pytest.mark.slow
def test_a_users_exact_law_plugin_is_named_on_a_foreign_wheel_angle_torque():
    """foreign_drives: A = 8 N*m sin(alpha2 + 0.31) on the wheel, 3 s. The plug-in -A*sin(alpha2 + phi) is the
    discovery, its amplitude within 3 of its uncertainties of 8 N*m (the phase: the foreign angle's origin is its own)."""
    from foreign_drives.drive import make_recording
    from foreign_drives.spec import EffectSpec as E
    from foreign_drives.spec import RecordingSpec, SensorNuisance

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    spec = RecordingSpec(label="wheel_angle", kind="one", width_m=0.006, eta_k=0.025, n1=0.89,
                         effects=(E("ripple_wheel_mesh", {"amplitude_Nm": 8.0, "order": 1, "phase_rad": 0.31}),),
                         sensor=SensorNuisance(), seed=311, duration_s=3.0).check()
    rec = make_recording(spec)
    meas = Measurement("foreign:wheel_angle", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    model = load_model(None, width_m=0.006, eta_k=0.025, n1=0.89, effect_files=[PLUGIN])
    d = diagnose(meas, model, effects=["wheel_angle_torque"], second=False).to_json()
    assert d["discovery"] == "wheel_angle_torque", d["message"]
    fit = d["discovery_parameters"]
    a, s = fit["parameters"]["amplitude_Nm"], fit["uncertainty"]["amplitude_Nm"]
    assert 0 < s < a / 3
    assert abs(a - 8.0) <= 3 * s
