"""The suites: TEST (a handful of short recordings the tests use, seeds 100-199), BENCH (>= 30 recordings of 4 s
with seeds 5000+, strengths and forms no test uses) and WIDTH_LOOP (hidden-effect drives at several widths
whose monitor width is checked before/after retraining, seeds 6000+).

Like real recorders, the recordings differ in chunk size, namespace, drive name, start time and the pulse
train's phase at the first sample; some carry sensor nuisance (white noise after the sensor, a 16-bit ADC,
shaft encoders with an arbitrary zero).
"""
from __future__ import annotations

import importlib

from .forms import ClutchContactHertz
from .spec import EffectSpec as E
from .spec import RecordingSpec, SensorNuisance

# realistic nuisance: MEMS noise after a ~1 kHz sensor bandwidth, 16-bit ADCs over +-50 g (a1) / +-4 g (a2)
ADC16 = SensorNuisance(a1_lsb_m_s2=2 * 50 * 9.81 / 2 ** 16, a2_lsb_m_s2=2 * 4 * 9.81 / 2 ** 16)
NOISY_ADC16 = SensorNuisance(a1_noise_rms_m_s2=0.05, a2_noise_rms_m_s2=0.01,
                             a1_lsb_m_s2=ADC16.a1_lsb_m_s2, a2_lsb_m_s2=ADC16.a2_lsb_m_s2)
ENCODERS_14BIT = SensorNuisance(encoder_counts_per_rev=2 ** 14, angle_offset_rad=0.37)
ENCODERS_16BIT = SensorNuisance(encoder_counts_per_rev=2 ** 16, angle_offset_rad=-1.21,
                                a1_lsb_m_s2=ADC16.a1_lsb_m_s2, a2_lsb_m_s2=ADC16.a2_lsb_m_s2)

CHUNKS = (1000, 500, 2500, 777, 5000, 1250, 2000, 640, 10000, 1024, 333)
NAMESPACES = ("", "line1/drive01", "press7", "cell2/axis3", "plant_b", "", "line2/drive14", "hall3/conveyor2",
              "", "test_rig")
PHASES = (0.05, 0.05, 0.1176, 0.05, 0.2192, 0.05, 0.0308, 0.05, 0.1644, 0.05, 0.05, 0.2036)


def _variety(i: int, seed: int) -> dict:
    """Recorder variety of the i-th recording of a suite."""
    ns = NAMESPACES[i % len(NAMESPACES)]
    return dict(seed=seed, chunk_samples=CHUNKS[i % len(CHUNKS)], namespace=ns,
                drive_name=(ns.split("/")[-1] if ns else "drive"), pulse_first_s=PHASES[i % len(PHASES)],
                start_time_ns=1_714_000_000_000_000_000 + i * 3_600_123_456_789)


def _suite(rows, first_seed: int, duration_s: float):
    out = []
    for i, (label, kind, w, eta, n1, effects, *extra) in enumerate(rows):
        kw = _variety(i, first_seed + i)
        if extra:
            kw.update(extra[0])
        out.append(RecordingSpec(label=label, kind=kind, width_m=w, eta_k=eta, n1=n1, effects=tuple(effects),
                                 duration_s=duration_s, **kw).check())
    return out


def _sig(signal, **p):
    return dict(signal=signal, **p)


# (label, kind, nominal width, eta_k, n1, effects[, extra spec fields])
BENCH_ROWS = [
    # ---- clean drives over the nominal grid (continuous values), some with sensor nuisance
    ("clean_w2.5_eta0.05_n0.97", "clean", 0.0025, 0.05, 0.97, []),
    ("clean_w3.1_eta0.0125_n0.89", "clean", 0.0031, 0.0125, 0.89, []),
    ("clean_w4.4_eta0.031_n0.93_adc", "clean", 0.0044, 0.031, 0.93, [], {"sensor": NOISY_ADC16}),
    ("clean_w5.0_eta0.025_n0.89", "clean", 0.005, 0.025, 0.89, []),
    ("clean_w6.2_eta0.044_n0.91_enc14", "clean", 0.0062, 0.044, 0.91, [], {"sensor": ENCODERS_14BIT}),
    ("clean_w7.1_eta0.0125_n0.97", "clean", 0.0071, 0.0125, 0.97, []),
    ("clean_w8.3_eta0.0375_n0.95", "clean", 0.0083, 0.0375, 0.95, []),
    ("clean_w9.0_eta0.019_n0.90_enc16", "clean", 0.009, 0.019, 0.90, [], {"sensor": ENCODERS_16BIT}),
    ("clean_w10_eta0.05_n0.89", "clean", 0.010, 0.05, 0.89, []),
    ("clean_w5.6_eta0.015_n0.96_adc", "clean", 0.0056, 0.015, 0.96, [], {"sensor": ADC16}),
    # ---- one effect: every catalogue family in a foreign form
    ("wheel_friction_loaddep_1.6Nm", "one", 0.0075, 0.025, 0.89,
     [E("wheel_friction_load_dependent", {"base_torque_Nm": 0.4, "load_coefficient_m": 0.04})]),
    ("wheel_drag_quadratic_1.2Nm", "one", 0.006, 0.03, 0.91,
     [E("wheel_drag_power", {"coefficient": 1.2 / 151.4 ** 2, "exponent": 2.0})]),
    ("wheel_stribeck_exp1_1.0Nm", "one", 0.008, 0.02, 0.93,
     [E("wheel_friction_stribeck_power", {"coulomb_torque_Nm": 0.6, "excess_torque_Nm": 1.4,
                                          "stribeck_speed_rad_s": 120.0, "exponent": 1.0})]),
    # motor-side torques show in the motor's mean speed (its slip), not in the accelerations: at 1.8-2 N*m they were
    # inside the speed's model-form tolerance (0.3 rad/s); 5 N*m (0.25 p.u.) is a failing bearing or a fan's load
    ("motor_friction_tanh_5Nm", "one", 0.005, 0.025, 0.89,
     [E("motor_friction_tanh", {"torque_Nm": 5.0, "smoothing_speed_rad_s": 20.0})]),
    ("clutch_hertz_softer_-0.3", "one", 0.005, 0.025, 0.89,
     [E("clutch_contact_hertz", {"stiffness": ClutchContactHertz.stiffness_for(-0.3, 1.5), "exponent": 1.5})]),
    ("clutch_hunt_crossley_+0.6", "one", 0.0075, 0.025, 0.89,
     [E("clutch_damping_hunt_crossley", {"lambda_Nms_per_rad2": 1800.0})]),
    ("shaft_hub_9000", "one", 0.0065, 0.0375, 0.91,
     [E("shaft_with_hub", {"stiffness_Nm_per_rad": 9000.0, "damping_Nms_per_rad": 40.0, "hub_inertia_kgm2": 0.03})]),
    ("mass_rail_friction_12N", "one", 0.0075, 0.025, 0.89,
     [E("mass_rail_friction", {"force_N": 12.0, "smoothing_speed_m_s": 0.05})]),
    ("motor_fan_load_0.25pu", "one", 0.004, 0.025, 0.93,
     [E("motor_fan_load", {"torque_Nm": 5.0, "reference_speed_rad_s": 151.4})]),
    ("ripple_cogging_6_12_18", "one", 0.0075, 0.025, 0.89,
     [E("ripple_motor_harmonics", {"orders": [6, 12, 18], "amplitudes_pu": [0.3, 0.12, 0.05],
                                   "phases_rad": [0.3, -1.1, 2.0]})]),
    ("ripple_order2_0.4", "one", 0.009, 0.0125, 0.95,
     [E("ripple_motor_harmonics", {"orders": [2], "amplitudes_pu": [0.4], "phases_rad": [-0.7]})]),
    ("ripple_em_order23", "one", 0.0055, 0.04, 0.89,
     [E("ripple_electromagnetic", {"relative_amplitude": 0.5, "order": 23, "phase_rad": 1.3})]),
    ("bias_a2_+2.0", "one", 0.009, 0.0375, 0.89, [E("bias_constant", _sig("a2", bias_m_s2=2.0))]),
    ("bias_a1_drift_-2", "one", 0.0075, 0.025, 0.91,
     [E("bias_drifting", _sig("a1", start_m_s2=-1.5, end_m_s2=-2.5))]),
    ("gain_a2_+0.15", "one", 0.006, 0.025, 0.89, [E("gain_constant", _sig("a2", relative_change=0.15))]),
    ("butterworth4_a1_800Hz", "one", 0.005, 0.02, 0.90,
     [E("lowpass_butterworth", _sig("a1", order=4, corner_hz=800.0))]),
    ("bessel2_a2_600Hz", "one", 0.007, 0.03, 0.92, [E("lowpass_bessel", _sig("a2", order=2, corner_hz=600.0))]),
    ("width_drift_5.0_to_6.2", "one", 0.005, 0.025, 0.89, [E("drift_width", {"change": 0.0012})]),
    ("mass_+0.3", "one", 0.0075, 0.025, 0.89, [E("drift_mass", {"relative_change": 0.3})]),
    ("wheel_inertia_+0.35", "one", 0.006, 0.0375, 0.93, [E("drift_wheel_inertia", {"relative_change": 0.35})]),
    ("spring_+0.5", "one", 0.0075, 0.025, 0.89, [E("drift_spring", {"relative_change": 0.5})]),
    ("absorber_eta_+0.6", "one", 0.005, 0.025, 0.89, [E("drift_eta_k", {"relative_change": 0.6})]),
    ("absorber_n1_+0.05", "one", 0.0075, 0.025, 0.90, [E("drift_n1", {"change": 0.05})]),
    ("working_resistance_+0.4", "one", 0.008, 0.02, 0.91, [E("drift_working_resistance", {"relative_change": 0.4})]),
    ("pulse_amplitude_-0.15", "one", 0.0065, 0.025, 0.89, [E("drift_pulse_amplitude", {"relative_change": -0.15})]),
    # ---- two effects
    ("friction+butterworth2_a1_700Hz", "two", 0.0075, 0.025, 0.89,
     [E("wheel_friction_tanh", {"torque_Nm": 1.2, "smoothing_speed_rad_s": 25.0}),
      E("lowpass_butterworth", _sig("a1", order=2, corner_hz=700.0))]),
    ("mass_drag_10N+fan_load", "two", 0.006, 0.03, 0.9,
     [E("mass_drag", {"coefficient_Ns2_per_m2": 10.0 / (151.4 * 0.15) ** 2}),
      E("motor_fan_load", {"torque_Nm": 1.5, "reference_speed_rad_s": 151.4})]),
    ("mass_+0.25+gain_a2_drift", "two", 0.0085, 0.025, 0.89,
     [E("drift_mass", {"relative_change": 0.25}), E("gain_drifting", _sig("a2", start_relative_change=-0.08,
                                                                             end_relative_change=-0.12))]),
    ("clutch_asym_far-0.35+wheel_mesh", "two", 0.005, 0.025, 0.89,
     [E("clutch_contact_asymmetric", {"drive_relative_change": 0.0, "far_relative_change": -0.35}),
      E("ripple_wheel_mesh", {"amplitude_Nm": 6.0, "order": 8, "phase_rad": 0.4})]),
    # ---- outside the catalogue (family None)
    ("outside_progressive_contact", "outside", 0.0075, 0.025, 0.89,
     [E("clutch_contact_progressive", {"p0_rad": 0.03})]),
    ("outside_vibration_107Hz", "outside", 0.006, 0.025, 0.89,
     [E("structural_vibration", {"amplitude_pu": 0.4, "frequency_hz": 107.0, "phase_rad": 0.0})]),
    # a weaker motor (was 'outside' until the catalogue had the motor's drifts; same row, same seed)
    ("rotor_resistance_+0.6", "one", 0.0075, 0.025, 0.91,
     [E("motor_rotor_resistance", {"relative_change": 0.6})]),
    # a non-linear law of the spring family (was labelled 'outside': around its operating extension it is a stiffer
    # spring, and the model with one is consistent with the recording in every view -- docs/foreign_drives.md)
    ("spring_hardening_z0_0.4", "one", 0.0045, 0.03, 0.89, [E("spring_hardening", {"z0_m": 0.4})]),
    ("outside_second_mode_120Hz", "outside", 0.0075, 0.025, 0.89,
     [E("second_torsional_mode", {"rim_fraction": 0.4,
                                  "stiffness_Nm_per_rad": (2 * 3.141592653589793 * 120.0) ** 2
                                  / (1 / (0.4 * 0.2) + 1 / (0.6 * 0.2 + 0.10950)),
                                  "damping_Nms_per_rad": 0.5})]),
    # appended (the rows above keep their seeds): two more effects outside the catalogue
    ("supply_voltage_-0.15", "one", 0.006, 0.03, 0.91, [E("supply_voltage", {"relative_change": -0.15})]),
    # a vibration at a fixed frequency next to an integer order of the rotation (6 x 24.1 Hz = 144.6 Hz): not a ripple
    ("outside_vibration_147Hz", "outside", 0.0075, 0.025, 0.89,
     [E("structural_vibration", {"amplitude_pu": 0.3, "frequency_hz": 147.0, "phase_rad": 0.7})]),
    # appended when the weaker motor joined the catalogue (the two rows above it left 'outside'): a preloaded jaw
    # insert, a contact law no catalogue effect has
    ("outside_contact_preload_12Nm", "outside", 0.0065, 0.03, 0.93,
     [E("clutch_contact_preload", {"preload_Nm": 12.0, "build_up_rad": 3e-4})]),
    ("outside_motor_inertia_+0.5", "outside", 0.0085, 0.02, 0.95, [E("motor_rotor_inertia", {"relative_change": 0.5})]),
]

WIDTH_LOOP_ROWS = [
    ("wl_width_drift_7.5_to_8.5", "one", 0.0075, 0.025, 0.89, [E("drift_width", {"change": 0.001})]),
    ("wl_wheel_friction_w3.75", "one", 0.00375, 0.025, 0.89,
     [E("wheel_friction_tanh", {"torque_Nm": 1.5, "smoothing_speed_rad_s": 15.0})]),
    ("wl_clutch_damping_+0.6_w9", "one", 0.009, 0.025, 0.89, [E("clutch_damping_value", {"relative_change": 0.6})]),
    ("wl_gain_a1_+0.12_w6", "one", 0.006, 0.025, 0.89, [E("gain_constant", _sig("a1", relative_change=0.12))]),
    ("wl_mass_force_-12N_w5", "one", 0.005, 0.025, 0.89, [E("mass_force_constant", {"force_N": -12.0})]),
]

TEST_ROWS = [
    ("t_clean_w5", "clean", 0.005, 0.025, 0.89, []),
    ("t_wheel_friction_2Nm", "one", 0.0075, 0.025, 0.89,
     [E("wheel_friction_tanh", {"torque_Nm": 2.0, "smoothing_speed_rad_s": 10.0})]),
    ("t_bessel4_a1_1kHz", "one", 0.006, 0.025, 0.89, [E("lowpass_bessel", _sig("a1", order=4, corner_hz=1000.0))]),
    ("t_two_width-0.5mm+bias_a1", "two", 0.006, 0.025, 0.89,
     [E("drift_width", {"change": -0.0005}), E("bias_constant", _sig("a1", bias_m_s2=1.0))], {"sensor": NOISY_ADC16}),
    ("t_outside_vibration_83Hz", "outside", 0.005, 0.025, 0.89,
     [E("structural_vibration", {"amplitude_pu": 0.3, "frequency_hz": 83.0, "phase_rad": 0.5})]),
]

# ---- issue 31 part 4: mechanisms OUTSIDE the catalogue (foreign_drives.outside_dev; the sealed half's rows are
# in foreign_drives.outside_sealed). Each row: one mechanism at a nominal width/eta_k/n1; controls: clean rows and
# width changes beside a mechanism (the width is the measurand there).
OUTSIDE_DEV_ROWS = [
    ("od_clean_w6.0_eta0.03_n0.92", "clean", 0.006, 0.03, 0.92, []),
    # a torque locked to the WHEEL angle: a cam and its follower (exact law: a plug-in, manifest truth.plugin)
    ("od_wheel_cam_4Nm_q0.6", "outside", 0.005, 0.025, 0.89,
     [E("wheel_cam_follower", {"amplitude_Nm": 4.0, "lift_ratio": 0.6, "phase_rad": 0.4})]),
    # a torque locked to the MOTOR angle: a single-acting crank pump (exact law: a plug-in)
    ("od_motor_crank_pump_0.3pu", "outside", 0.0075, 0.0375, 0.93,
     [E("motor_crank_pump", {"amplitude_pu": 0.3, "phase_rad": -1.0})]),
    # the wheel-angle law of issue 31's set 3: -A*sin(alpha2 + phi) (the cam without lift)
    ("od_wheel_unbalance_6Nm", "outside", 0.01, 0.05, 0.97,
     [E("wheel_cam_follower", {"amplitude_Nm": 6.0, "lift_ratio": 0.0, "phase_rad": 2.2})]),
    ("od_mass_creep_20N", "outside", 0.0065, 0.02, 0.90,
     [E("mass_creeping_resistance", {"force_N": 20.0, "creep_time_s": 4.0})]),
    ("od_wheel_process_brake_3Nm", "outside", 0.008, 0.03, 0.95,
     [E("wheel_process_brake", {"torque_Nm": 3.0, "build_up_s": 0.005})]),
    ("od_clutch_gap_drag_0.6", "outside", 0.0055, 0.025, 0.91,
     [E("clutch_gap_drag", {"damping_Nms_per_rad": 0.6})]),
    ("od_motor_carriage_coupling_3", "outside", 0.009, 0.015, 0.89,
     [E("motor_carriage_coupling", {"coefficient_Nms_per_m": 3.0})]),
    ("od_a1_rotating_gravity", "outside", 0.004, 0.045, 0.96,
     [E("a1_rotating_gravity", {"amplitude_m_s2": 9.81, "phase_rad": 0.9})]),
    # width changes beside a mechanism (the true width is nominal + change)
    ("od_width_5.0_to_6.2+gap_drag", "outside", 0.005, 0.025, 0.89,
     [E("drift_width", {"change": 0.0012}), E("clutch_gap_drag", {"damping_Nms_per_rad": 0.5})]),
    ("od_width_7.5_to_8.3+wheel_cam", "outside", 0.0075, 0.025, 0.89,
     [E("drift_width", {"change": 0.0008}), E("wheel_cam_follower", {"amplitude_Nm": 3.0, "lift_ratio": 0.3,
                                                                      "phase_rad": -2.0})]),
    ("od_width_4.0_to_5.0+crank_pump", "outside", 0.004, 0.03, 0.93,
     [E("drift_width", {"change": 0.001}), E("motor_crank_pump", {"amplitude_pu": 0.25, "phase_rad": 1.7})]),
    ("od_clean_w8.7_eta0.018_n0.94", "clean", 0.0087, 0.018, 0.94, []),
]

# ---- issue 31 part 4, second set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev2;
# the second sealed half's rows are in foreign_drives.outside_sealed2). Seeds 7300+.
OUTSIDE_DEV2_ROWS = [
    ("od2_clean_w5.8_eta0.028_n0.91", "clean", 0.0058, 0.028, 0.91, []),
    # dry friction on the jaw faces: a hysteresis in the penetration (mu = 0.15 of the contact stiffness)
    ("od2_clutch_jaw_dry_friction", "outside", 0.006, 0.025, 0.90,
     [E("clutch_jaw_dry_friction", {"coefficient_Nm_per_rad": 450.0, "sign_speed_rad_s": 0.2})]),
    # a force on the mass locked to the WHEEL angle (exact law: a plug-in)
    ("od2_mass_eccentric_roller_4N", "outside", 0.0075, 0.03, 0.93,
     [E("mass_eccentric_roller", {"amplitude_N": 4.0, "phase_rad": -0.8})]),
    # the spring extension beyond a threshold brakes the motor (exact law: a plug-in)
    ("od2_motor_overload_band_brake", "outside", 0.005, 0.02, 0.89,
     [E("motor_overload_band_brake", {"coefficient_Nm_per_m": 300.0, "threshold_m": 0.295})]),
    ("od2_wheel_timed_brake_3Nm", "outside", 0.0085, 0.035, 0.95,
     [E("wheel_timed_brake", {"torque_Nm": 3.0, "start_s": 1.7, "build_up_s": 0.1})]),
    ("od2_mass_floor_vibration_3N", "outside", 0.0065, 0.04, 0.92,
     [E("mass_floor_vibration", {"amplitude_N": 3.0, "frequency_hz": 37.0, "phase_rad": 0.3})]),
    ("od2_a1_soft_saturation", "outside", 0.0045, 0.025, 0.94, [E("a1_soft_saturation", {"gain_inverse_limit_s2_per_m": 0.01})]),
    ("od2_a2_bracket_tilt", "outside", 0.007, 0.0175, 0.90,
     [E("a2_bracket_tilt", {"gain_m_s2_per_m": 19.6, "centre_m": 0.29})]),
    # width changes beside a mechanism (the true width is nominal + change)
    ("od2_width_5.5_to_6.5+dry_friction", "outside", 0.0055, 0.025, 0.91,
     [E("drift_width", {"change": 0.001}),
      E("clutch_jaw_dry_friction", {"coefficient_Nm_per_rad": 400.0, "sign_speed_rad_s": 0.2})]),
    ("od2_width_8.0_to_8.9+eccentric_roller", "outside", 0.008, 0.025, 0.89,
     [E("drift_width", {"change": 0.0009}), E("mass_eccentric_roller", {"amplitude_N": 3.5, "phase_rad": 2.0})]),
    ("od2_clean_w3.6_eta0.045_n0.95", "clean", 0.0036, 0.045, 0.95, []),
]

# ---- issue 31 part 4, third set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev3;
# the third sealed half's rows are in foreign_drives.outside_sealed3). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 7800+ (7600+ are bench/_workbench/width_caveat.py's).
OUTSIDE_DEV3_ROWS = [
    # a load on the motor after each stroke's end, decaying (a pump recharging the accumulator)
    ("od3_motor_accumulator_recharge", "outside", 0.006, 0.03, 0.92,
     [E("motor_accumulator_recharge", {"torque_Nm": 4.0, "decay_s": 0.04})]),
    # a brake on the wheel gated by the jaw's angle difference (engaged while the load runs ahead)
    ("od3_wheel_weston_brake", "outside", 0.0075, 0.02, 0.90,
     [E("wheel_weston_brake", {"torque_Nm": 4.0, "engage_width_rad": 0.003})]),
    # the backlash's boundaries moving with the motor angle at order 2 (a Cardan shaft at ~3.2 degrees; at 4e-3 rad,
    # 7 degrees, the jaw rattled: 117 onsets in 4 s; at 1.2e-3 one entry re-triggered)
    ("od3_clutch_cardan_error", "outside", 0.0085, 0.035, 0.94,
     [E("clutch_cardan_error", {"amplitude_rad": 0.0008, "order": 2, "phase_rad": 0.7})]),
    # a force on the carriage following the pulse 20 ms late with a 10 ms lag
    ("od3_mass_pneumatic_holdback", "outside", 0.005, 0.025, 0.89,
     [E("mass_pneumatic_holdback", {"force_N": 12.0, "delay_s": 0.02, "lag_s": 0.01})]),
    ("od3_clean_w7.8_eta0.04_n0.95", "clean", 0.0078, 0.04, 0.95, []),
    ("od3_a2_transmitter_deadband", "outside", 0.0065, 0.0175, 0.91,
     [E("a2_transmitter_deadband", {"deadband_m_s2": 0.4})]),
    # a relay with hysteresis on the motor speed (a two-point switch every 0.2 ms); noise-free it switches on and off
    # once per pulse period, on 70 % of the time (at 153/150 rad/s: on 4 %)
    ("od3_motor_speed_relay_load", "outside", 0.0045, 0.045, 0.96,
     [E("motor_speed_relay_load", {"torque_Nm": 3.0, "on_above_rad_s": 152.0, "off_below_rad_s": 149.0})]),
    ("od3_a2_stroke_ringing", "outside", 0.0095, 0.0225, 0.89,
     [E("a2_stroke_ringing", {"amplitude_m_s2": 2.0, "frequency_hz": 173.0, "decay_s": 0.02})]),
]

# ---- issue 31 part 4, fourth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev4;
# the fourth sealed half's rows are in foreign_drives.outside_sealed4). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 8000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The fourth set").
OUTSIDE_DEV4_ROWS = [
    # an extra load on every third stroke (a piercing station working on every third part)
    ("od4_motor_nth_stroke_pierce", "outside", 0.0065, 0.03, 0.91,
     [E("motor_nth_stroke_pierce", {"torque_Nm": 8.0, "every_n": 3, "station": 1})]),
    # a flywheel behind a sprag clutch on the wheel shaft: dragged up above its speed, coasting below (3 N*m*s/rad
    # moved a2 by 0.025 m/s^2 rms: x3)
    ("od4_wheel_freewheel_flywheel", "outside", 0.0085, 0.02, 0.94,
     [E("wheel_freewheel_flywheel", {"coefficient_Nms_per_rad": 9.0, "lock_time_s": 0.02, "coast_time_s": 20.0})]),
    # a viscoelastic jaw insert: a Maxwell branch of twice the contact stiffness relaxing in 10 ms (2000 N*m/rad moved
    # a2 by 0.024 m/s^2 rms: x3)
    ("od4_clutch_viscoelastic_insert", "outside", 0.005, 0.04, 0.90,
     [E("clutch_viscoelastic_insert", {"stiffness_Nm_per_rad": 6000.0, "relaxation_time_s": 0.01})]),
    # a rail clamp fired for 30 ms when the spring stretches through 0.31 m (it runs 0.28-0.32 m)
    ("od4_mass_spring_switch_clamp", "outside", 0.0075, 0.025, 0.93,
     [E("mass_spring_switch_clamp", {"force_N": 10.0, "trigger_extension_m": 0.31, "hold_s": 0.03})]),
    ("od4_clean_w6.2_eta0.0175_n0.96", "clean", 0.0062, 0.0175, 0.96, []),
    # a slew-rate limit of 1.5e6 m/s^3 (the jaw's impacts reach ~8e6 m/s^3 on a1)
    ("od4_a1_isolation_amp_slew", "outside", 0.0055, 0.045, 0.89,
     [E("a1_isolation_amp_slew", {"slew_rate_m_s3": 1.5e6})]),
    # a1 held over 0.5 rad of each motor revolution (3.3 ms in 42 ms)
    ("od4_a1_telemetry_shadow_hold", "outside", 0.009, 0.015, 0.92,
     [E("a1_telemetry_shadow_hold", {"window_rad": 0.5, "start_rad": 1.0})]),
    # a speed loop on the carriage, 1 ms scan, 3 ms dead time, v_ref = the clean drive's mean mass speed (same seed)
    ("od4_mass_servo_assist_sampled", "outside", 0.004, 0.035, 0.95,
     [E("mass_servo_assist_sampled", {"gain_Ns_per_m": 60.0, "reference_speed_m_s": 22.717, "scan_s": 0.001,
                                      "latency_scans": 3})]),
]

# ---- issue 31 part 4, fifth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev5;
# the fifth sealed half's rows are in foreign_drives.outside_sealed5). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 8200+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The fifth set").
OUTSIDE_DEV5_ROWS = [
    # a governor's brake band behind a linkage with 1 rad/s of play, biting above 151 rad/s (the drive runs 147-154);
    # 2 N*m*s/rad moved a2 by 0.039 m/s^2 rms: x1.91
    ("od5_motor_governor_linkage_play", "outside", 0.0058, 0.0275, 0.93,
     [E("motor_governor_linkage_play", {"gain_Nms_per_rad": 3.81, "play_rad_s": 1.0, "set_speed_rad_s": 151.0})]),
    # the spring's cable winding onto the drum (~150 turns in the run-in and 4 s); 0.2 mm per turn moved a2 by
    # 0.023 m/s^2 rms: x3.22
    ("od5_wheel_rope_drum_layers", "outside", 0.0082, 0.0225, 0.90,
     [E("wheel_rope_drum_layers", {"growth_m_per_turn": 6.43e-4})]),
    # the jaw hub's run-out: the contact torque modulated once per wheel revolution; +-30 % moved a2 by 0.040 m/s^2
    # rms: x1.88
    ("od5_clutch_hub_runout", "outside", 0.0048, 0.0375, 0.95,
     [E("clutch_hub_runout", {"gain": 0.563, "phase_rad": 0.5})]),
    # a 2 kg absorber tuned to 40 Hz (near the jaw's ~33 Hz mode), 5 % damping
    ("od5_mass_tuned_absorber", "outside", 0.0068, 0.02, 0.91,
     [E("mass_tuned_absorber", {"mass_kg": 2.0, "frequency_hz": 40.0, "damping_ratio": 0.05})]),
    ("od5_clean_w7.2_eta0.0325_n0.92", "clean", 0.0072, 0.0325, 0.92, []),
    # a tare every 0.37 s (not a multiple of the 0.25 s pulse period) over the 5 ms before it
    ("od5_a2_daq_autozero", "outside", 0.0092, 0.045, 0.94,
     [E("a2_daq_autozero", {"period_s": 0.37, "window_s": 0.005, "first_s": 0.2})]),
    # the insert softening as it heats. At 0.02/J with tau 0.5 s it moved a2 by 0.0040 m/s^2 rms (g*theta ~ 0.1, nearly
    # constant: a stiffness drift), and the x18.7 the criterion asked would soften it by g*theta ~ 2 (a pulling
    # contact). Changed before any diagnose: tau 0.05 s (a surface layer, its heat varying within each stroke), g 0.1/J
    # (g*theta 0.005-0.15; a2 0.0033 m/s^2 rms); at 0.4/J the softening feeds back (softer, deeper, hotter) and the
    # simulation did not finish in 5 minutes. BELOW the visibility criterion (docs/foreign_drives.md "The fifth set")
    ("od5_clutch_insert_heating", "outside", 0.0062, 0.0155, 0.89,
     [E("clutch_insert_heating", {"softening_per_J": 0.1, "cooling_time_s": 0.05})]),
    # a stuck bit of weight 0.25 m/s^2 in an ADC over +-4 g (a2 swings over several m/s^2)
    ("od5_a2_stuck_adc_bit", "outside", 0.0042, 0.03, 0.96,
     [E("a2_stuck_adc_bit", {"bit_weight_m_s2": 0.25, "range_m_s2": 39.24})]),
]

# ---- issue 31 part 4, sixth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev6;
# the sixth sealed half's rows are in foreign_drives.outside_sealed6). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 8400+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The sixth set").
OUTSIDE_DEV6_ROWS = [
    # a 0.03 kg*m^2 brake disc (0.27 J1) on a slip hub of 2 N*m
    ("od6_motor_slip_hub_flywheel", "outside", 0.0061, 0.0285, 0.92,
     [E("motor_slip_hub_flywheel", {"inertia_kgm2": 0.03, "slip_torque_Nm": 2.0})]),
    # an idler in a +-4 mrad mesh backlash, 200 Hz on its flank, drag 0.5/s; 0.005 kg*m^2 moved a2 by 0.0147 m/s^2 rms:
    # x5.12
    ("od6_wheel_idler_gear_rattle", "outside", 0.0079, 0.022, 0.91,
     [E("wheel_idler_gear_rattle", {"inertia_kgm2": 0.0256, "backlash_rad": 0.004, "contact_frequency_hz": 200.0,
                                    "contact_damping_ratio": 0.1, "drag_per_s": 0.5})]),
    # the contact torque capped at 40 N*m (an impact's elastic torque reaches ~39, with its damping ~105-120)
    ("od6_clutch_torque_limiter", "outside", 0.0052, 0.036, 0.94, [E("clutch_torque_limiter", {"limit_Nm": 40.0})]),
    # 1.5 N of rail friction per part, the tray emptied every 4 strokes
    ("od6_mass_tray_parts", "outside", 0.0069, 0.019, 0.90,
     [E("mass_tray_parts", {"force_per_part_N": 1.5, "every_n": 4, "first_empty": 1})]),
    ("od6_clean_w7.4_eta0.0265_n0.95", "clean", 0.0074, 0.0265, 0.95, []),
    # +-10 % gain for the two directions
    ("od6_a2_bilinear_gain", "outside", 0.0087, 0.041, 0.93, [E("a2_bilinear_gain", {"asymmetry": 0.1})]),
    # a module over +-2.4 m/s^2 (the clean drive of seed 8406: |a2| up to 2.62, its 90th percentile 2.30), 2 ms to recover
    ("od6_a2_overload_recovery", "outside", 0.0046, 0.0315, 0.96,
     [E("a2_overload_recovery", {"range_m_s2": 2.4, "recovery_s": 0.002})]),
    # a brake chopped at 5 ms, its duty 0 at 149 rad/s and 1 at 155 (the drive runs 147-154); 3 N*m moved a2 by 0.0346
    # m/s^2 rms: x2.17
    ("od6_wheel_pwm_brake", "outside", 0.0058, 0.0245, 0.89,
     [E("wheel_pwm_brake", {"torque_Nm": 6.5, "carrier_period_s": 0.005, "zero_duty_speed_rad_s": 149.0,
                            "full_duty_span_rad_s": 6.0})]),
]

# ---- issue 31 part 4, seventh set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev7;
# the seventh sealed half's rows are in foreign_drives.outside_sealed7). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 8600+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The seventh set").
OUTSIDE_DEV7_ROWS = [
    # a retarder disc, its coefficient +-60 % over a turn; 0.03 N*m*s/rad (4.5 N*m at 150 rad/s) moved a2 by 0.0385
    # m/s^2 rms: x1.95
    ("od7_motor_eddy_disc_wobble", "outside", 0.0063, 0.0295, 0.91,
     [E("motor_eddy_disc_wobble", {"drag_Nms_per_rad": 0.0584, "wobble": 0.6, "phase_rad": 0.8})]),
    # a catch tripping at 153 rad/s (the clean drive of seed 8600: Omega2 148.2-153.6, its 95th percentile 153.3)
    ("od7_wheel_overspeed_latch_brake", "outside", 0.0077, 0.0215, 0.93,
     [E("wheel_overspeed_latch_brake", {"torque_Nm": 4.0, "trip_speed_rad_s": 153.0})]),
    # magnets whose pull falls to a quarter 2 mrad from a face (the gap's half ~30-50 mrad); 5 N*m at a face moved a2 by
    # 0.0148 m/s^2 rms: x5.06
    ("od7_clutch_magnetic_face_latch", "outside", 0.0054, 0.0345, 0.90,
     [E("clutch_magnetic_face_latch", {"pull_Nm": 25.3, "decay_angle_rad": 0.002})]),
    # a 10 N rail brake after 10 ms above 22.74 m/s (the clean drive of seed 8600: v 22.67-22.80, median 22.72)
    ("od7_mass_debounced_overspeed_brake", "outside", 0.0071, 0.0195, 0.96,
     [E("mass_debounced_overspeed_brake", {"force_N": 10.0, "max_speed_m_s": 22.74, "delay_s": 0.01})]),
    ("od7_clean_w7.6_eta0.0275_n0.93", "clean", 0.0076, 0.0275, 0.93, []),
    # the reading 10 % low during each pulse
    ("od7_a2_supply_sag_gain", "outside", 0.0089, 0.0385, 0.92, [E("a2_supply_sag_gain", {"sag": 0.1})]),
    # a 6 N*m feed over 15 rad (about 0.1 s at 150 rad/s, past the 60 ms pulse)
    ("od7_motor_metered_roll_feed", "outside", 0.0047, 0.0325, 0.94,
     [E("motor_metered_roll_feed", {"torque_Nm": 6.0, "feed_angle_rad": 15.0})]),
    # a median over 353 samples (7 ms); 51 samples (1 ms) moved a2 by 0.0108 m/s^2 rms: x6.92
    ("od7_a2_median_spike_filter", "outside", 0.0059, 0.0225, 0.89,
     [E("a2_median_spike_filter", {"window_samples": 353})]),
]

# ---- issue 31 part 4, eighth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev8;
# the eighth sealed half's rows are in foreign_drives.outside_sealed8). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 8800+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The eighth set").
OUTSIDE_DEV8_ROWS = [
    # a peak at 150 rad/s, half of it 1.5 rad/s away (a clean drive's Omega1: 147-153.6 rad/s for 99 %); 3 N*m a
    # priori, a2 0.0351: scaled once x2.14
    ("od8_motor_fan_blade_flutter", "outside", 0.0066, 0.0265, 0.92,
     [E("motor_fan_blade_flutter", {"peak_torque_Nm": 6.41, "resonance_speed_rad_s": 150.0, "half_width_rad_s": 1.5})]),
    # 2 N*m per rad/s of the measured speed above 152 rad/s (a clean drive's Omega2: 148.3-153.4 rad/s for 99 %)
    ("od8_wheel_period_tacho_brake", "outside", 0.0074, 0.0205, 0.94,
     [E("wheel_period_tacho_brake", {"gain_Nm_s_per_rad": 2.0, "set_speed_rad_s": 152.0, "phase_rad": 0.5})]),
    # a detent of pitch 20 mrad (the gap's half ~30-50 mrad: a few wells across it); 2 N*m a priori, a2 0.0287:
    # scaled once x2.61
    ("od8_clutch_ball_detent", "outside", 0.0081, 0.0355, 0.91,
     [E("clutch_ball_detent", {"detent_torque_Nm": 5.22, "pitch_rad": 0.02})]),
    # 10 N per m/s of the stroke's mean speed from 22.55 m/s, within +-20 N (a clean drive's v: 22.63-22.78 m/s)
    ("od8_mass_run_to_run_booster", "outside", 0.0049, 0.0315, 0.95,
     [E("mass_run_to_run_booster", {"gain_N_s_per_m": 10.0, "reference_speed_m_s": 22.55, "force_limit_N": 20.0})]),
    ("od8_clean_w6.8_eta0.0245_n0.90", "clean", 0.0068, 0.0245, 0.90, []),
    # wrapping beyond +-1 m/s^2: the a priori +-1.55 (from another seed's clean a2) never wrapped in the visibility
    # simulation (this seed's |a2| <= 1.21); set once to 1.0, about the 95th percentile of this seed's clean |a2|
    ("od8_a2_fixed_point_wrap", "outside", 0.0058, 0.0185, 0.93, [E("a2_fixed_point_wrap", {"range_m_s2": 1.0})]),
    # a 25 Hz chatter of 8 N*m above 151 rad/s
    ("od8_wheel_brake_squeal", "outside", 0.0087, 0.0295, 0.89,
     [E("wheel_brake_squeal", {"torque_Nm": 8.0, "frequency_hz": 25.0, "growth_per_rad_s": 0.1,
                               "onset_speed_rad_s": 151.0})]),
    # steps per sample at 50 kHz: 0.01-0.08 m/s^2 a priori, a2 0.00596: both scaled once x12.6
    ("od8_a2_delta_modulator_codec", "outside", 0.0063, 0.0375, 0.96,
     [E("a2_delta_modulator_codec", {"min_step_m_s2": 0.126, "max_step_m_s2": 1.01, "growth": 1.5, "decay": 0.8})]),
]

# ---- issue 31 part 4, ninth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev9;
# the ninth sealed half's rows are in foreign_drives.outside_sealed9). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 9000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The ninth set").
OUTSIDE_DEV9_ROWS = [
    # a blower at 150 rad/s behind a clutch engaging over +-2 rad/s (a clean drive's Omega1: 147-153.6 rad/s); 2 N*m a
    # priori, a2 0.0234: scaled once x3.20
    ("od9_motor_centrifugal_clutch_blower", "outside", 0.0067, 0.0255, 0.92,
     [E("motor_centrifugal_clutch_blower", {"blower_torque_Nm": 6.40, "engage_speed_rad_s": 150.0,
                                            "engage_width_rad_s": 2.0})]),
    # a drag over 1 rad of every third wheel turn; 5 N*m a priori, a2 0.0282: scaled once x2.66
    ("od9_wheel_geneva_indexer", "outside", 0.0073, 0.0215, 0.94,
     [E("wheel_geneva_indexer", {"torque_Nm": 13.3, "turns_per_index": 3, "window_rad": 1.0, "phase_rad": 0.5})]),
    # 50 N per m/s of the chamber's speed above 22.6 m/s (a clean drive's v: 22.63-22.78 m/s); 5 ms up, 100 ms down
    ("od9_mass_check_valve_damper", "outside", 0.0050, 0.0305, 0.95,
     [E("mass_check_valve_damper", {"coefficient_N_s_per_m": 50.0, "crack_speed_m_s": 22.6, "rise_time_s": 0.005,
                                    "fall_time_s": 0.1})]),
    ("od9_clean_w6.9_eta0.0235_n0.90", "clean", 0.0069, 0.0235, 0.90, []),
    # a play of +-0.3 m/s^2 (a clean drive's a2: -1.61..1.12 m/s^2 for 99 %)
    ("od9_a2_loose_seismic_mass", "outside", 0.0057, 0.0195, 0.93, [E("a2_loose_seismic_mass", {"play_m_s2": 0.3})]),
    # 20 N per m of the spring's extension (k = 100 N/m: mu = 0.2)
    ("od9_mass_cable_guide_friction", "outside", 0.0088, 0.0285, 0.89,
     [E("mass_cable_guide_friction", {"coefficient_N_per_m": 20.0, "sign_speed_m_s": 0.1})]),
    # steps of 5 mm/s^2, a time constant of 32 samples (0.64 ms), stalled within +-0.08 m/s^2
    ("od9_a2_fixed_point_smoothing", "outside", 0.0064, 0.0365, 0.96,
     [E("a2_fixed_point_smoothing", {"step_m_s2": 0.005, "shift": 5})]),
    # disc springs over a free height of 5 mrad (k_c = 3000 N*m/rad: ~7 mrad at 20 N*m); 5 N*m a priori, a2 0.0402:
    # scaled once x1.86; last, seed 9007: added after the other rows' visibility was measured (its first realisation,
    # on the penetration while the contact law pushes, made the generator chatter at the contact's end with the noise
    # on; outside_dev9's docstring)
    ("od9_clutch_belleville_snap_through", "outside", 0.0082, 0.0345, 0.91,
     [E("clutch_belleville_snap_through", {"spring_torque_Nm": 9.32, "free_height_rad": 0.005})]),
]

# ---- issue 31 part 4, tenth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev10;
# the tenth sealed half's rows are in foreign_drives.outside_sealed10). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 10000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The tenth set").
OUTSIDE_DEV10_ROWS = [
    # a ring at 80 Hz decaying over 20 ms from each stroke's start; 5 N*m a priori, a2 0.0115: scaled once x6.54
    ("od10_motor_stroke_torsional_ring", "outside", 0.0063, 0.0265, 0.92,
     [E("motor_stroke_torsional_ring", {"amplitude_Nm": 32.7, "frequency_hz": 80.0, "decay_time_s": 0.02})]),
    # 0.05 N*m*s/rad (~7.5 N*m at 150 rad/s, ~1.1 kW) cut out above 300 J, back below 200 J, cooling over 0.5 s
    ("od10_wheel_thermal_cutout_brake", "outside", 0.0079, 0.0215, 0.93,
     [E("wheel_thermal_cutout_brake", {"coefficient_Nm_s_per_rad": 0.05, "cooling_time_s": 0.5, "off_above_J": 300.0,
                                       "on_below_J": 200.0})]),
    # a leaf spring across the jaw during each stroke; 60 N*m/rad a priori, a2 0.0392: scaled once x1.91
    ("od10_clutch_stroke_leaf_spring", "outside", 0.0054, 0.0355, 0.90,
     [E("clutch_stroke_leaf_spring", {"stiffness_Nm_per_rad": 115.0})]),
    # a rail brake toggled each time z rises past 0.31 m, re-armed below 0.295 m (a clean drive's z: 0.284-0.322 m);
    # 3 N a priori, a2 0.0460: scaled once x1.63
    ("od10_mass_impulse_relay_brake", "outside", 0.0087, 0.0305, 0.94,
     [E("mass_impulse_relay_brake", {"force_N": 4.89, "on_above_m": 0.31, "rearm_below_m": 0.295})]),
    ("od10_clean_w7.1_eta0.0245_n0.92", "clean", 0.0071, 0.0245, 0.92, []),
    # a codec of full scale 200 m/s^2 (a clean drive's a1: -104..100 m/s^2 for 99 %)
    ("od10_a1_mu_law_codec", "outside", 0.0068, 0.0185, 0.95, [E("a1_mu_law_codec", {"full_scale_m_s2": 200.0})]),
    # relaxing over 5 ms (a clean drive's slip: -5..5 rad/s); 1 N*m*s/rad a priori, a2 0.0301: scaled once x2.49
    ("od10_clutch_viscoelastic_coupling", "outside", 0.0056, 0.0295, 0.89,
     [E("clutch_viscoelastic_coupling", {"coefficient_Nm_s_per_rad": 2.49, "relaxation_time_s": 0.005})]),
    # 3 N*m rising over 10 ms from each contact's start
    ("od10_wheel_contact_interlock_brake", "outside", 0.0075, 0.0375, 0.91,
     [E("wheel_contact_interlock_brake", {"torque_Nm": 3.0, "rise_time_s": 0.01})]),
]

# ---- issue 31 part 4, eleventh set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev11;
# the eleventh sealed half's rows are in foreign_drives.outside_sealed11). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 11000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The eleventh set").
OUTSIDE_DEV11_ROWS = [
    # 2 N*m per rad/s of wheel speed above 151 rad/s on the motor (a clean drive's Omega: 147.6-153.7 rad/s)
    ("od11_motor_wheel_runaway_governor", "outside", 0.0064, 0.0270, 0.93,
     [E("motor_wheel_runaway_governor", {"gain_Nm_s_per_rad": 2.0, "set_speed_rad_s": 151.0})]),
    # 3 N*m on above 152 rad/s, held 20 ms after
    ("od11_wheel_off_delay_overspeed_brake", "outside", 0.0078, 0.0220, 0.91,
     [E("wheel_off_delay_overspeed_brake", {"torque_Nm": 3.0, "trip_speed_rad_s": 152.0, "off_delay_s": 0.02})]),
    # 1 N*m*s/rad one way (a clean drive's slip: -5..5 rad/s)
    ("od11_clutch_overrunning_viscous_coupling", "outside", 0.0055, 0.0350, 0.92,
     [E("clutch_overrunning_viscous_coupling", {"coefficient_Nm_s_per_rad": 1.0})]),
    # +-2 N outside 22.72 +- 0.02 m/s (a clean drive's v: 22.67-22.77 m/s)
    ("od11_mass_dead_band_speed_switch", "outside", 0.0086, 0.0300, 0.95,
     [E("mass_dead_band_speed_switch", {"force_N": 2.0, "reference_speed_m_s": 22.72, "half_band_m_s": 0.02,
                                        "edge_width_m_s": 0.002})]),
    ("od11_clean_w7.2_eta0.0250_n0.90", "clean", 0.0072, 0.0250, 0.90, []),
    # a 50 Hz notch of quality 1
    ("od11_a2_mains_notch_filter", "outside", 0.0069, 0.0190, 0.94,
     [E("a2_mains_notch_filter", {"notch_hz": 50.0, "quality": 1.0})]),
    # 5 N on a 0.1 m air column, gamma 1.4 (a clean drive's z: 0.284-0.322 m)
    ("od11_mass_stroke_trapped_air_cushion", "outside", 0.0057, 0.0290, 0.90,
     [E("mass_stroke_trapped_air_cushion", {"force_N": 5.0, "column_m": 0.1, "exponent": 1.4})]),
    # +-2 N*m, a new level every 0.1 s
    ("od11_wheel_upstream_tension_steps", "outside", 0.0074, 0.0370, 0.92,
     [E("wheel_upstream_tension_steps", {"torque_Nm": 2.0, "step_s": 0.1, "first_step_s": 0.05, "seed": 11})]),
]

# ---- issue 31 part 4, twelfth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev12;
# the twelfth sealed half's rows are in foreign_drives.outside_sealed12). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 12000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The twelfth set").
OUTSIDE_DEV12_ROWS = [
    # choked at 140 rad/s (a clean drive's Omega: 147.6-153.7 rad/s); c = 1.43e-4 N*m*s^2/rad^2 (about 3 N*m) a priori,
    # a2 0.0114: scaled once x6.56 (about 20 N*m)
    ("od12_motor_choked_water_brake", "outside", 0.0064, 0.0270, 0.93,
     [E("motor_choked_water_brake", {"coefficient_Nm_s2_per_rad2": 9.38e-4, "choke_speed_rad_s": 140.0})]),
    # 2 N*m per litre of fill; 0.1 l/rad in, 15 l/s/sqrt(l) out (about 1 l at 150 rad/s, filling in ~0.1 s)
    ("od12_wheel_pump_fed_retarder", "outside", 0.0078, 0.0220, 0.91,
     [E("wheel_pump_fed_retarder", {"torque_Nm_per_l": 2.0, "inflow_l_per_rad": 0.1, "drain_l_s_per_sqrt_l": 15.0})]),
    # 1.5 N*m*s/rad at 150 rad/s (a clean drive's slip: -5..5 rad/s)
    ("od12_clutch_hydrodynamic_coupling", "outside", 0.0055, 0.0350, 0.92,
     [E("clutch_hydrodynamic_coupling", {"coefficient_Nm_s_per_rad": 1.5})]),
    # at 150 rad/s; 0.1 N*s/m (about 2.3 N at a clean drive's 22.7 m/s) a priori, a2 0.0362: scaled once x2.07
    ("od12_mass_tacho_fed_eddy_brake", "outside", 0.0086, 0.0300, 0.95,
     [E("mass_tacho_fed_eddy_brake", {"coefficient_N_s_per_m": 0.207})]),
    ("od12_clean_w7.2_eta0.0250_n0.90", "clean", 0.0072, 0.0250, 0.90, []),
    # a 30 % echo 0.1 ms late
    ("od12_a2_cable_echo", "outside", 0.0069, 0.0190, 0.94,
     [E("a2_cable_echo", {"reflection": 0.3, "delay_samples": 5})]),
    # 3 N behind a slot of +-5 mm (a clean drive's z: 0.284-0.322 m)
    ("od12_mass_lost_motion_friction_link", "outside", 0.0057, 0.0290, 0.90,
     [E("mass_lost_motion_friction_link", {"force_N": 3.0, "half_slot_m": 0.005})]),
    # 0.02 N*m*s/rad during the pulse (about 3 N*m)
    ("od12_wheel_stroke_gated_cushion_pump", "outside", 0.0074, 0.0370, 0.92,
     [E("wheel_stroke_gated_cushion_pump", {"coefficient_Nm_s_per_rad": 0.02})]),
]

# ---- issue 31 part 4, thirteenth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev13;
# the thirteenth sealed half's rows are in foreign_drives.outside_sealed13). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 13000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The thirteenth set").
OUTSIDE_DEV13_ROWS = [
    # above 100 rad/s (a clean drive's Omega: 147.6-153.7 rad/s); c = 10 N*m (about 4 N*m) a priori, a2 0.0125: scaled
    # once x6.00 (about 24 N*m)
    ("od13_motor_paste_mixer", "outside", 0.0063, 0.0275, 0.92,
     [E("motor_paste_mixer", {"coefficient_Nm": 60.05, "reference_speed_rad_s": 100.0})]),
    # 0.03 N*m*s/rad up to 150 rad/s (about 4.5 N*m), constant above
    ("od13_wheel_relief_valve_pump", "outside", 0.0079, 0.0225, 0.90,
     [E("wheel_relief_valve_pump", {"coefficient_Nm_s_per_rad": 0.03, "relief_speed_rad_s": 150.0})]),
    # 2 N*m once slipping by more than ~0.5 rad/s (a clean drive's slip: -5..5 rad/s)
    ("od13_clutch_hysteresis_coupling", "outside", 0.0056, 0.0355, 0.93,
     [E("clutch_hysteresis_coupling", {"torque_Nm": 2.0, "smoothing_speed_rad_s": 0.2})]),
    # towards 0.1513 m * Omega2 (22.7 m/s at 150 rad/s; a clean drive's v: 22.67-22.77 m/s); 2 N*s/m a priori, a2
    # 0.0467: scaled once x1.61
    ("od13_mass_wheel_tracking_conveyor", "outside", 0.0085, 0.0305, 0.94,
     [E("mass_wheel_tracking_conveyor", {"coefficient_N_s_per_m": 3.211, "belt_radius_m": 0.1513})]),
    ("od13_clean_w7.3_eta0.0255_n0.91", "clean", 0.0073, 0.0255, 0.91, []),
    # 0.1 m/s^2 at 150 rad/s, 4 pole pairs (about 95 Hz)
    ("od13_a2_motor_magnet_pickup", "outside", 0.0068, 0.0195, 0.95,
     [E("a2_motor_magnet_pickup", {"amplitude_m_s2": 0.1, "pole_pairs": 4, "phase_rad": 0.3})]),
    # for 20 ms from each rise of Omega1 through 152 rad/s (a clean drive's Omega: 147.6-153.7 rad/s); 3 N*m a priori,
    # a2 0.0278: scaled once x2.69
    ("od13_motor_overspeed_timed_brake", "outside", 0.0058, 0.0285, 0.91,
     [E("motor_overspeed_timed_brake", {"torque_Nm": 8.082, "trip_speed_rad_s": 152.0, "hold_s": 0.02})]),
    # 2 cm^3/rad in, 20 cm^3/s/sqrt(cm^3) out; 1 N*m per cm^3 a priori, a2 0.000948: scaled once x79.1
    ("od13_clutch_slip_pumped_plate_clutch", "outside", 0.0075, 0.0365, 0.93,
     [E("clutch_slip_pumped_plate_clutch", {"torque_Nm_per_cm3": 79.12, "inflow_cm3_per_rad": 2.0,
                                            "drain_cm3_s_per_sqrt_cm3": 20.0})]),
]

# ---- issue 31 part 4, fourteenth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev14;
# the fourteenth sealed half's rows are in foreign_drives.outside_sealed14). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 14000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The fourteenth set"). A clean drive's ranges (seed 14004, 4 s): Omega1 146.9-154.2,
# Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s, D -0.062..0.062 rad (beta 0.049 rad).
OUTSIDE_DEV14_ROWS = [
    # on the motor while sin(alpha2 + 0.5) > 0; 3 N*m a priori, a2 0.0228: scaled once x3.29
    ("od14_motor_wheel_cam_brake", "outside", 0.0064, 0.0265, 0.93,
     [E("motor_wheel_cam_brake", {"torque_Nm": 9.864, "phase_rad": 0.5})]),
    # beyond 150 rad/s; 0.5 N*m*s/rad a priori (up to about 2 N*m), a2 0.0351: scaled once x2.14
    ("od14_wheel_bypassed_retarder", "outside", 0.0078, 0.0215, 0.91,
     [E("wheel_bypassed_retarder", {"coefficient_Nm_s_per_rad": 1.069, "bypass_speed_rad_s": 150.0})]),
    # 50 N*m/rad at 150 rad/s (about 3 N*m at the faces)
    ("od14_clutch_centrifugal_leaf_spring", "outside", 0.0057, 0.0345, 0.92,
     [E("clutch_centrifugal_leaf_spring", {"stiffness_Nm_per_rad": 50.0})]),
    # 80 N/m over 0.295-0.315 m (0..1.6 N; z 0.291-0.326 m with it: both ends and the ramp). As first written, 200 N/m
    # over 0.29-0.31 m out-pulled the spring's 100 N/m: the carriage ran to the loop's lifted end and stayed there (z
    # 0.321-0.357 m, a constant force; a2 0.0595 not used); then 50 N/m over 0.29-0.33 m kept z inside the ramp (a plain
    # spring; a2 0.0438 not used); the third, this, a2 0.0558: as written
    ("od14_mass_festoon_cable_loop", "outside", 0.0084, 0.0295, 0.95,
     [E("mass_festoon_cable_loop", {"weight_N_per_m": 80.0, "centre_m": 0.305, "half_range_m": 0.01})]),
    ("od14_clean_w7.3_eta0.0255_n0.91", "clean", 0.0073, 0.0255, 0.91, []),
    # about 22.7 m/s; 1 (m/s^2)/(m/s) a priori, a2 0.0397: scaled once x1.89
    ("od14_a2_velocity_sensitivity", "outside", 0.0069, 0.0205, 0.94,
     [E("a2_velocity_sensitivity", {"sensitivity_per_s": 1.891, "zero_speed_m_s": 22.7})]),
    # above 152 rad/s of the held peak, bleeding off in 0.5 s; 1 N*m*s/rad a priori, a2 0.0150: scaled once x5.02
    ("od14_motor_drag_pointer_governor_brake", "outside", 0.0059, 0.0275, 0.90,
     [E("motor_drag_pointer_governor_brake", {"coefficient_Nm_s_per_rad": 5.016, "set_speed_rad_s": 152.0,
                                              "release_time_s": 0.5})]),
    # 200 N*m/rad, the hub slipping at 0.01 rad (2 N*m)
    ("od14_clutch_friction_slider_spring", "outside", 0.0076, 0.0355, 0.94,
     [E("clutch_friction_slider_spring", {"stiffness_Nm_per_rad": 200.0, "slip_twist_rad": 0.01})]),
]

# ---- issue 31 part 4, fifteenth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev15;
# the fifteenth sealed half's rows are in foreign_drives.outside_sealed15). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 15000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The fifteenth set"). The a-priori values are read off the fourteenth set's clean drive
# (seed 14004, 4 s: Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s) and the
# documented impacts (the deepest penetration 0.013 rad at 7.5 mm; the drive side's steady one about r*F0/k_c).
OUTSIDE_DEV15_ROWS = [
    # 1 N*m*s/rad of |Omega1 - Omega2| (a few N*m while the halves cross the gap)
    ("od15_motor_slip_monitor_brake", "outside", 0.0066, 0.0275, 0.92,
     [E("motor_slip_monitor_brake", {"coefficient_Nm_s_per_rad": 1.0})]),
    # beyond 22.72 m/s; 40 N*m*s/m a priori (up to about 3 N*m), a2 0.0386: scaled once x1.94
    ("od15_wheel_carriage_runaway_brake", "outside", 0.0081, 0.0235, 0.94,
     [E("wheel_carriage_runaway_brake", {"coefficient_Nm_s_per_m": 77.78, "trip_speed_m_s": 22.72})]),
    # 5e4 N*m/rad^3 (2.9 N*m at the faces, beta 0.0387 rad)
    ("od15_clutch_hardening_elastomer_spider", "outside", 0.0058, 0.0325, 0.91,
     [E("clutch_hardening_elastomer_spider", {"stiffness_Nm_per_rad3": 5.0e4})]),
    # about 0.295 m during each stroke; 60 N/m a priori (about +-1.5 N), a2 0.0336: scaled once x2.23
    ("od15_mass_stroke_gas_spring", "outside", 0.0074, 0.0285, 0.96,
     [E("mass_stroke_gas_spring", {"stiffness_N_per_m": 133.9, "reference_m": 0.295})]),
    ("od15_clean_w7.7_eta0.0265_n0.93", "clean", 0.0077, 0.0265, 0.93, []),
    # 0.1 m/s^2 while the drive faces touch
    ("od15_a2_drive_face_ground_loop", "outside", 0.0063, 0.0215, 0.90,
     [E("a2_drive_face_ground_loop", {"offset_m_s2": 0.1})]),
    # 200 N*m/m above 0.30 m of the extension's peak since the stroke began (up to about 4 N*m)
    ("od15_wheel_ratchet_cable_tensioner", "outside", 0.0085, 0.0345, 0.92,
     [E("wheel_ratchet_cable_tensioner", {"coefficient_Nm_per_m": 200.0, "reference_m": 0.30})]),
    # 4 N for 20 ms from each impact deeper than 4 mrad
    ("od15_mass_knock_triggered_rail_brake", "outside", 0.0069, 0.0305, 0.95,
     [E("mass_knock_triggered_rail_brake", {"force_N": 4.0, "trigger_penetration_rad": 0.004, "hold_s": 0.02})]),
]

# ---- issue 31 part 4, sixteenth set: mechanisms outside the catalogue of other kinds again (foreign_drives.outside_dev16;
# the sixteenth sealed half's rows are in foreign_drives.outside_sealed16). One mechanism per row at its own nominal
# conditions, one clean control. Seeds 16000+. Each strength set by one simulation against the clean drive of the same
# seed (docs/foreign_drives.md "The sixteenth set"). The a-priori values are read off the fifteenth set's documented
# clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s; the pulse 60 ms every
# 0.25 s).
OUTSIDE_DEV16_ROWS = [
    # 3 N*m at 30 ms into each stroke, 5 ms half-width a priori, a2 0.0203: scaled once x3.70
    ("od16_motor_flying_shear_cut", "outside", 0.0070, 0.0260, 0.93,
     [E("motor_flying_shear_cut", {"torque_Nm": 11.09, "cut_delay_s": 0.03, "half_width_s": 0.005})]),
    # 8.9e-5 N*m*s^2/rad^2 (about 2 N*m at 150 rad/s, helping the wheel)
    ("od16_wheel_hydrostatic_booster", "outside", 0.0062, 0.0300, 0.91,
     [E("wheel_hydrostatic_booster", {"coefficient_Nm_s2_per_rad2": 8.9e-5})]),
    # 100 N*m/m above 0.28 m, tanh of the slip over 0.5 rad/s (up to about 4 N*m)
    ("od16_clutch_cable_loaded_friction_plate", "outside", 0.0080, 0.0240, 0.94,
     [E("clutch_cable_loaded_friction_plate", {"coefficient_Nm_per_m": 100.0, "reference_m": 0.28,
                                               "slip_scale_rad_s": 0.5})]),
    # 8.9e-5 N*s^2/rad^2 (2 N at 150 rad/s), phase 0.7
    ("od16_mass_motor_unbalance_frame_shake", "outside", 0.0058, 0.0330, 0.92,
     [E("mass_motor_unbalance_frame_shake", {"coefficient_N_s2_per_rad2": 8.9e-5, "phase_rad": 0.7})]),
    ("od16_clean_w7.1_eta0.0285_n0.95", "clean", 0.0071, 0.0285, 0.95, []),
    # 0.1 m/s^2, saturating over 0.5 m/s
    ("od16_a2_drag_chain_triboelectric", "outside", 0.0086, 0.0210, 0.90,
     [E("a2_drag_chain_triboelectric", {"offset_m_s2": 0.1, "speed_scale_m_s": 0.5})]),
    # 4 N for 20 ms from each rise of the wheel speed through 152 rad/s
    ("od16_mass_wheel_overspeed_timed_rail_brake", "outside", 0.0066, 0.0350, 0.96,
     [E("mass_wheel_overspeed_timed_rail_brake", {"force_N": 4.0, "trip_speed_rad_s": 152.0, "hold_s": 0.02})]),
    # 50 N*m/m above 0.30 m of the extension's peak since the stroke began (up to about 1 N*m) a priori, a2 0.0278:
    # scaled once x2.70
    ("od16_motor_peak_tension_regen_brake", "outside", 0.0076, 0.0225, 0.93,
     [E("motor_peak_tension_regen_brake", {"coefficient_Nm_per_m": 134.7, "reference_m": 0.30})]),
]

# ---- issue 31 part 4, seventeenth set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev17; the seventeenth sealed half's rows are in foreign_drives.outside_sealed17). One mechanism
# per row at its own nominal conditions, one clean control. Seeds 17000+. Each strength set by one simulation against
# the clean drive of the same seed (docs/foreign_drives.md "The seventeenth set"). The a-priori values are read off the
# fifteenth set's documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80
# m/s; the pulse 60 ms every 0.25 s).
OUTSIDE_DEV17_ROWS = [
    # 1.5 N*m per whole centimetre of the extension above 0.28 m (up to about 6 N*m)
    ("od17_motor_tension_staged_eddy_brake", "outside", 0.0069, 0.0265, 0.92,
     [E("motor_tension_staged_eddy_brake", {"torque_per_stage_Nm": 1.5, "threshold_m": 0.28, "step_m": 0.01})]),
    # 2 N*m at order 1/7 of the wheel's turn (about 3.4 Hz), phase 0.5
    ("od17_wheel_geared_lubricator_crank", "outside", 0.0061, 0.0310, 0.94,
     [E("wheel_geared_lubricator_crank", {"torque_Nm": 2.0, "reduction": 7.0, "phase_rad": 0.5})]),
    # 0.2 N*m*s^2/rad^2 (5 N*m at 5 rad/s of slip) a priori, a2 0.0391: scaled once x1.92
    ("od17_clutch_orifice_rotary_damper", "outside", 0.0083, 0.0235, 0.90,
     [E("clutch_orifice_rotary_damper", {"coefficient_Nm_s2_per_rad2": 0.3832})]),
    # 3 N, saturating over 0.05 m/s of the speed difference
    ("od17_mass_motor_pinch_roll_drag", "outside", 0.0064, 0.0345, 0.95,
     [E("mass_motor_pinch_roll_drag", {"force_N": 3.0, "speed_scale_m_s": 0.05})]),
    ("od17_clean_w7.3_eta0.0275_n0.93", "clean", 0.0073, 0.0275, 0.93, []),
    # 2 /m about 0.30 m (a2's gain about -5 % ... +4 % over the extension's range) a priori, a2 0.0148: scaled once
    # x5.06
    ("od17_a2_strain_sensitive_gain", "outside", 0.0087, 0.0215, 0.96,
     [E("a2_strain_sensitive_gain", {"gain_per_m": 10.11, "reference_m": 0.30})]),
    # 1 N*m*s/rad of the slip sampled at each impact (a few N*m)
    ("od17_wheel_impact_sampled_anti_clatter", "outside", 0.0067, 0.0300, 0.91,
     [E("wheel_impact_sampled_anti_clatter", {"coefficient_Nm_s_per_rad": 1.0})]),
    # 40 N*m/rad about the stroke's starting angle (a few N*m over the gap)
    ("od17_clutch_stroke_reanchored_torsion_bar", "outside", 0.0077, 0.0250, 0.97,
     [E("clutch_stroke_reanchored_torsion_bar", {"stiffness_Nm_per_rad": 40.0})]),
]

# ---- issue 31 part 4, eighteenth set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev18; the eighteenth sealed half's rows are in foreign_drives.outside_sealed18). One mechanism
# per row at its own nominal conditions, one clean control. Seeds 18000+. Each strength set by one simulation against
# the clean drive of the same seed (docs/foreign_drives.md "The eighteenth set"). The a-priori values are read off the
# fifteenth set's documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80
# m/s; the pulse 60 ms every 0.25 s).
OUTSIDE_DEV18_ROWS = [
    # 0.01 N*m*s/rad (1.5 N*m at 150 rad/s) on 0.4 m of every 1.2 m (about 19 Hz at the carriage's speed) a priori,
    # a2 0.0181: scaled once x4.14
    ("od18_motor_rail_section_dynamo", "outside", 0.0070, 0.0260, 0.93,
     [E("motor_rail_section_dynamo", {"coefficient_Nm_s_per_rad": 0.04142, "pitch_m": 1.2, "live_m": 0.4,
                                      "offset_m": 0.1})]),
    # 40 N*m*s/m of the stroke's peak carriage speed above 22.70 m/s (up to about 4 N*m)
    ("od18_wheel_stroke_peak_carriage_speed_brake", "outside", 0.0062, 0.0305, 0.95,
     [E("wheel_stroke_peak_carriage_speed_brake", {"coefficient_Nm_s_per_m": 40.0, "reference_speed_m_s": 22.70})]),
    # 3 N*m pull-out at 2 rad/s of slip
    ("od18_clutch_induction_slip_coupling", "outside", 0.0082, 0.0240, 0.91,
     [E("clutch_induction_slip_coupling", {"pullout_torque_Nm": 3.0, "pullout_slip_rad_s": 2.0})]),
    # 3 N from a carriage speed above 22.76 m/s to the next stroke
    ("od18_mass_stroke_rearmed_overspeed_catch", "outside", 0.0066, 0.0340, 0.94,
     [E("mass_stroke_rearmed_overspeed_catch", {"force_N": 3.0, "trip_speed_m_s": 22.76})]),
    ("od18_clean_w7.4_eta0.0270_n0.92", "clean", 0.0074, 0.0270, 0.92, []),
    # 0.01 s^2/m (a2's gain +-1 % per m/s^2 of a1)
    ("od18_a2_reference_shared_with_a1", "outside", 0.0086, 0.0220, 0.97,
     [E("a2_reference_shared_with_a1", {"gain_per_m_s2": 0.01})]),
    # 40 N*m/rad about an anchor creeping at most 0.2 rad/s
    ("od18_clutch_creeping_anchor_torsion_bar", "outside", 0.0078, 0.0285, 0.90,
     [E("clutch_creeping_anchor_torsion_bar", {"stiffness_Nm_per_rad": 40.0, "creep_rad_s": 0.2})]),
    # 3 N, a section every 0.6 m (about 38 sections a second), seed 7
    ("od18_mass_rail_section_slopes", "outside", 0.0065, 0.0250, 0.96,
     [E("mass_rail_section_slopes", {"force_N": 3.0, "section_m": 0.6, "offset_m": 0.0, "seed": 7.0})]),
]

# ---- issue 31 part 4, nineteenth set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev19; the nineteenth sealed half's rows are in foreign_drives.outside_sealed19). One mechanism
# per row at its own nominal conditions, one clean control. Seeds 19000+. Each strength set by one simulation against
# the clean drive of the same seed (docs/foreign_drives.md "The nineteenth set"). The a-priori values are read off the
# documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s; the pulse
# 60 ms every 0.25 s; the gap's half-width beta = w/r, about 0.045 rad).
OUTSIDE_DEV19_ROWS = [
    # 2 N*m at full charge, charged over 0.1 s after each stroke's start a priori, a2 0.0498: scaled once x1.51
    ("od19_motor_accumulator_charging_pump", "outside", 0.0072, 0.0255, 0.93,
     [E("motor_accumulator_charging_pump", {"torque_Nm": 3.011, "charge_time_s": 0.1})]),
    # 2 N*m, a roller every 2 m (about 11 a second at the carriage's speed) a priori, a2 0.0415: scaled once x1.81
    ("od19_wheel_cable_guide_rollers", "outside", 0.0063, 0.0300, 0.95,
     [E("wheel_cable_guide_rollers", {"torque_Nm": 3.619, "pitch_m": 2.0, "offset_m": 0.0})]),
    # 1000 N*m/(rad*m) above 0.26 m (about 2 N*m at the faces)
    ("od19_clutch_tension_fed_torsion_bellows", "outside", 0.0081, 0.0240, 0.91,
     [E("clutch_tension_fed_torsion_bellows", {"stiffness_Nm_per_rad_m": 1000.0, "reference_m": 0.26})]),
    # 3 N over 0.6 rad of each turn (about 4 ms, 24 times a second)
    ("od19_mass_drum_grooving_crossover", "outside", 0.0067, 0.0335, 0.94,
     [E("mass_drum_grooving_crossover", {"force_N": 3.0, "arc_rad": 0.6, "angle_rad": 0.0})]),
    ("od19_clean_w7.3_eta0.0265_n0.93", "clean", 0.0073, 0.0265, 0.93, []),
    # 0.1 m/s^2 (a slope of 1 %), a wavelength of 1.5 m (about 15 Hz at the carriage's speed)
    ("od19_a2_wavy_track_tilt", "outside", 0.0085, 0.0225, 0.96,
     [E("a2_wavy_track_tilt", {"amplitude_m_s2": 0.1, "wavelength_m": 1.5, "offset_m": 0.0})]),
    # 1 N*m*s/rad of the slip averaged over 10 ms a priori, a2 0.0493: scaled once x1.52
    ("od19_wheel_slip_averaging_anti_clatter", "outside", 0.0077, 0.0280, 0.90,
     [E("wheel_slip_averaging_anti_clatter", {"coefficient_Nm_s_per_rad": 1.520, "window_scans": 50.0})]),
    # 0.04 N*m/W of the contact's peak power, bleeding over 50 ms
    ("od19_motor_impact_severity_brake", "outside", 0.0066, 0.0245, 0.97,
     [E("motor_impact_severity_brake", {"coefficient_Nm_per_W": 0.04, "decay_s": 0.05})]),
]

# ---- issue 31 part 4, twentieth set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev20; the twentieth sealed half's rows are in foreign_drives.outside_sealed20). One mechanism
# per row at its own nominal conditions, one clean control. Seeds 20000+. Each strength set by one simulation against
# the clean drive of the same seed (docs/foreign_drives.md "The twentieth set"). The a-priori values are read off the
# documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s; the pulse
# 60 ms every 0.25 s; the gap's half-width beta = w/r, about 0.049 rad).
OUTSIDE_DEV20_ROWS = [
    # 2 N*m just before a mark, a mark every 1 m (about 23 a second at the carriage's speed) a priori, a2 0.0131:
    # scaled once x5.73
    ("od20_motor_travel_marker_cylinder", "outside", 0.0074, 0.0260, 0.94,
     [E("motor_travel_marker_cylinder", {"torque_Nm": 11.46, "pitch_m": 1.0, "offset_m": 0.0})]),
    # 2 N*m once the slip is well above 1 rad/s (a width of 0.5 rad/s) a priori, a2 0.0330: scaled once x2.27
    ("od20_wheel_gerotor_slip_assist", "outside", 0.0066, 0.0285, 0.92,
     [E("wheel_gerotor_slip_assist", {"torque_Nm": 4.545, "onset_rad_s": 1.0, "width_rad_s": 0.5})]),
    # 60 N*m/rad at the current's peak (about 3 N*m at the faces), 50 Hz mains a priori, a2 0.0419: scaled once x1.79
    ("od20_clutch_half_wave_magnet_centring", "outside", 0.0080, 0.0250, 0.96,
     [E("clutch_half_wave_magnet_centring", {"stiffness_Nm_per_rad": 107.4, "mains_hz": 50.0, "phase_rad": 0.0})]),
    # 5 N/m of the extension (up to 3 N), a level-wind cycle every 8 turns (about 3 a second)
    ("od20_mass_level_wind_fleet_angle", "outside", 0.0071, 0.0305, 0.90,
     [E("mass_level_wind_fleet_angle", {"coefficient_N_per_m": 5.0, "turns_per_cycle": 8.0, "angle_rad": 0.0})]),
    ("od20_clean_w7.0_eta0.0270_n0.94", "clean", 0.0070, 0.0270, 0.94, []),
    # 5e-5 rad per N*m (a web of about 20 kN*m/rad): about 0.17 m/s^2 per N*m of the jaw's torque at 150 rad/s
    ("od20_a1_coupling_flange_twist", "outside", 0.0083, 0.0235, 0.95,
     [E("a1_coupling_flange_twist", {"twist_rad_per_Nm": 5e-5})]),
    # K_p 50 N*m/m, K_i 1000 N*m/(m*s), holding 0.30 m, at most 3 N*m
    ("od20_wheel_tension_pi_brake", "outside", 0.0068, 0.0265, 0.91,
     [E("wheel_tension_pi_brake", {"gain_Nm_per_m": 50.0, "integral_Nm_per_m_s": 1000.0, "reference_m": 0.30,
                                   "max_torque_Nm": 3.0})]),
    # 2 N*m full, the relay on above 1 rad/s and off below 0, filling over 20 ms, draining over 50 ms
    ("od20_motor_slip_relay_cylinder_brake", "outside", 0.0076, 0.0245, 0.97,
     [E("motor_slip_relay_cylinder_brake", {"torque_Nm": 2.0, "on_above_rad_s": 1.0, "off_below_rad_s": 0.0,
                                            "fill_time_s": 0.02, "drain_time_s": 0.05})]),
]

# ---- issue 31 part 4, twenty-first set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev21; the twenty-first sealed half's rows are in foreign_drives.outside_sealed21). One
# mechanism per row at its own nominal conditions, one clean control. Seeds 21000+. Each strength set by one simulation
# against the clean drive of the same seed (docs/foreign_drives.md "The twenty-first set"). The a-priori values are read
# off the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s; the
# pulse 60 ms every 0.25 s; the gap's half-width beta = w/r, about 0.043-0.056 rad).
OUTSIDE_DEV21_ROWS = [
    # 0.15 N*m per (rad/s)^2 above 150 rad/s (about 2.6 N*m at 154 rad/s) a priori, a2 0.0229: scaled once x3.28
    ("od21_motor_self_excited_generator", "outside", 0.0073, 0.0255, 0.93,
     [E("motor_self_excited_generator", {"coefficient_Nm_s2_per_rad2": 0.4913, "critical_speed_rad_s": 150.0})]),
    # 3 N*m once the faces have been more than 10 mrad apart for 4 ms
    ("od21_wheel_gap_guard_holding_brake", "outside", 0.0067, 0.0290, 0.95,
     [E("wheel_gap_guard_holding_brake", {"torque_Nm": 3.0, "gap_rad": 0.01, "delay_s": 0.004})]),
    # 30 N*m/rad (about 1.5 N*m across the gap), relaxing over 50 ms a priori, a2 0.0282: scaled once x2.66
    ("od21_clutch_viscoelastic_boot", "outside", 0.0081, 0.0245, 0.91,
     [E("clutch_viscoelastic_boot", {"stiffness_Nm_per_rad": 79.84, "relaxation_s": 0.05})]),
    # 100 N per m/s of the speed's 10 ms mean from 22.73 m/s, within +-5 N
    ("od21_mass_averaged_speed_booster", "outside", 0.0069, 0.0315, 0.94,
     [E("mass_averaged_speed_booster", {"gain_N_s_per_m": 100.0, "reference_m_s": 22.73, "limit_m_s": 0.05,
                                        "window_scans": 50.0})]),
    ("od21_clean_w7.7_eta0.0235_n0.92", "clean", 0.0077, 0.0235, 0.92, []),
    # 0.5 m/s^2 per p.u. of torque (t_e about 0.4-0.95 p.u.: up to about 0.5 m/s^2), 50 Hz mains a priori, a1 0.2205:
    # scaled once x1.70
    ("od21_a1_torque_following_hum", "outside", 0.0084, 0.0230, 0.96,
     [E("a1_torque_following_hum", {"coefficient_m_s2": 0.8503, "mains_hz": 50.0, "phase_rad": 0.0})]),
    # 64 pulses a turn (about 1.5 kHz at the drum's speed) a priori, a2 0.0108: scaled once x6.92 (its strength the
    # hold's length, 1/N: 64/6.92 = 9.25 pulses a turn, taken whole, 9; about 215 Hz)
    ("od21_a2_drum_encoder_clocked_hold", "outside", 0.0064, 0.0270, 0.90,
     [E("a2_drum_encoder_clocked_hold", {"pulses_per_turn": 9.0, "angle_rad": 0.0})]),
    # 1 N*m*s/rad aligned, a land of half-width 10 mrad a priori, a2 0.0482: scaled once x1.56
    ("od21_clutch_metering_land_damper", "outside", 0.0079, 0.0260, 0.97,
     [E("clutch_metering_land_damper", {"coefficient_Nm_s_per_rad": 1.557, "land_rad": 0.01})]),
]

# ---- issue 31 part 4, twenty-second set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev22; the twenty-second sealed half's rows are in foreign_drives.outside_sealed22). One
# mechanism per row at its own nominal conditions, one clean control. Seeds 22000+. Each strength set by one simulation
# against the clean drive of the same seed (docs/foreign_drives.md "The twenty-second set"). The a-priori values are read
# off the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s; the
# pulse 60 ms every 0.25 s; T_b = 20 N*m, the rim's mean load r*F0 about 4.5 N*m).
OUTSIDE_DEV22_ROWS = [
    # 2 N*m once the jaw transmits more than about 6 N*m (over 2 N*m)
    ("od22_motor_load_sensing_brake", "outside", 0.0074, 0.0250, 0.94,
     [E("motor_load_sensing_brake", {"torque_Nm": 2.0, "threshold_Nm": 6.0, "width_Nm": 2.0})]),
    # 3 N*m above 22.76 m/s and for 20 ms after
    ("od22_wheel_carriage_overspeed_off_delay_brake", "outside", 0.0068, 0.0285, 0.92,
     [E("wheel_carriage_overspeed_off_delay_brake", {"torque_Nm": 3.0, "trip_speed_m_s": 22.76,
                                                     "off_delay_s": 0.02})]),
    # 0.3 N*m*s^2/rad^2 a priori (up to about 3 N*m at a slip of 3 rad/s sampled and passed), a2 0.003812: scaled once
    # x19.7
    ("od22_clutch_stroke_set_eddy_coupling", "outside", 0.0080, 0.0240, 0.96,
     [E("clutch_stroke_set_eddy_coupling", {"coefficient_Nm_s2_per_rad2": 5.9024})]),
    # K_p 200 N*s/m, K_i 2000 N/m, at most 5 N, above 22.75 m/s
    ("od22_mass_pi_speed_limiter", "outside", 0.0070, 0.0300, 0.93,
     [E("mass_pi_speed_limiter", {"gain_N_s_per_m": 200.0, "integral_N_per_m": 2000.0, "max_force_N": 5.0,
                                  "reference_m_s": 22.75})]),
    ("od22_clean_w7.6_eta0.0245_n0.95", "clean", 0.0076, 0.0245, 0.95, []),
    # 0.5 per (Omega1/150 rad/s)^2 - 1 (a gain within about -2 % .. +3 % over the speed's range)
    ("od22_a1_centripetal_sensitivity", "outside", 0.0083, 0.0265, 0.90,
     [E("a1_centripetal_sensitivity", {"gain_change": 0.5, "calibration_speed_rad_s": 150.0})]),
    # full scale 100 m/s^2, a boxcar of 64 bits (1.3 ms)
    ("od22_a2_sigma_delta_converter", "outside", 0.0065, 0.0255, 0.97,
     [E("a2_sigma_delta_converter", {"full_scale_m_s2": 100.0, "window_samples": 64.0})]),
    # 0.5 N*m at each of 12 teeth, decaying over 0.1 rad (about 290 clicks a second); a2 0.000357, left as written,
    # INVISIBLE (below a tenth of the criterion): its single scaling, x210 (T 105 N*m), lies beyond the form's bound
    # (50 N*m) and at five times the motor's base torque, so it was not made (docs/foreign_drives.md)
    ("od22_motor_ratchet_backstop_clicks", "outside", 0.0078, 0.0235, 0.91,
     [E("motor_ratchet_backstop_clicks", {"torque_Nm": 0.5, "teeth": 12.0, "angle_rad": 0.0, "decay_rad": 0.1})]),
]

# ---- issue 31 part 4, twenty-third set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev23; the twenty-third sealed half's rows are in foreign_drives.outside_sealed23). One
# mechanism per row at its own nominal conditions, one clean control. Seeds 23000+. Each strength set by one simulation
# against the clean drive of the same seed (docs/foreign_drives.md "The twenty-third set"). The a-priori values are read
# off the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the slip within about +-5 rad/s, the
# jaw's angle difference within +-0.064 rad, z 0.288-0.313 m, v 22.67-22.77 m/s, t_e 0.44-0.89 p.u.; a2 rms about 1
# m/s^2; the pulse 60 ms every 0.25 s; T_b = 20 N*m).
OUTSIDE_DEV23_ROWS = [
    # +-2 N*m over +-0.03 m/s of the carriage's speed about 22.72 m/s
    ("od23_motor_line_speed_follower_trim", "outside", 0.0071, 0.0255, 0.93,
     [E("motor_line_speed_follower_trim", {"torque_Nm": 2.0, "reference_m_s": 22.72, "span_m_s": 0.03})]),
    # 200 N*m per m of the stroke's mean extension over 0.296 m (about 0.5 N*m a stroke at first), within +-3 N*m
    ("od23_wheel_run_to_run_tension_trim", "outside", 0.0082, 0.0240, 0.95,
     [E("wheel_run_to_run_tension_trim", {"gain_Nm_per_m": 200.0, "reference_m": 0.296, "limit_Nm": 3.0})]),
    # 40 N*m*s/rad^2 (about 2 N*m at a twist of 0.05 rad and a slip of 1 rad/s)
    ("od23_clutch_tapered_vane_damper", "outside", 0.0068, 0.0275, 0.91,
     [E("clutch_tapered_vane_damper", {"coefficient_Nm_s_per_rad2": 40.0})]),
    # 1 N a step, 8 steps (8 N of hold-back at the start, released step by step), about 0.299 m +-6 mm, a step each
    # 10 ms outside the band
    ("od23_mass_tension_step_holdback", "outside", 0.0077, 0.0230, 0.97,
     [E("mass_tension_step_holdback", {"force_per_step_N": 1.0, "reference_m": 0.299, "dead_band_m": 0.006,
                                       "step_time_s": 0.01, "steps": 8.0})]),
    ("od23_clean_w7.2_eta0.0250_n0.96", "clean", 0.0072, 0.0250, 0.96, []),
    # 1 m/s^2 per p.u. of the torque (an offset of about 0.6 m/s^2 swinging by about +-0.2)
    ("od23_a1_stator_field_pickup", "outside", 0.0085, 0.0265, 0.92,
     [E("a1_stator_field_pickup", {"coefficient_m_s2": 1.0})]),
    # 0.1 s^2/m of a2's mean square over 50 ms (a zero shift of about 0.1 m/s^2)
    ("od23_a2_vibration_rectification", "outside", 0.0066, 0.0245, 0.94,
     [E("a2_vibration_rectification", {"coefficient_s2_per_m": 0.1, "time_constant_s": 0.05})]),
    # 2 N*m*s/rad when fully on, a 10 ms period, the duty from 0 at no slip to 1 at 3 rad/s
    ("od23_clutch_pwm_slip_coupling", "outside", 0.0079, 0.0285, 0.90,
     [E("clutch_pwm_slip_coupling", {"coefficient_Nm_s_per_rad": 2.0, "period_s": 0.01, "zero_duty_slip_rad_s": 0.0,
                                     "full_duty_span_rad_s": 3.0})]),
]

# ---- issue 31 part 4, twenty-fourth set: mechanisms outside the catalogue of other kinds again
# (foreign_drives.outside_dev24; the twenty-fourth sealed half's rows are in foreign_drives.outside_sealed24). One
# mechanism per row at its own nominal conditions, one clean control. Seeds 24000+. Each strength set by one simulation
# against the clean drive of the same seed (docs/foreign_drives.md "The twenty-fourth set"). The a-priori values are read
# off the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the slip within about +-5 rad/s, the
# jaw's angle difference within +-0.064 rad about a gap of +-0.051 rad, z 0.288-0.313 m, v 22.67-22.77 m/s, the
# carriage's position about 45-136 m over a 4 s recording; a1 within +-127 m/s^2; the pulse 60 ms every 0.25 s; T_b =
# 20 N*m).
OUTSIDE_DEV24_ROWS = [
    # 2 N*m a priori once the jaw has stayed more than 4 mrad deep for 4 ms; a2 0.0253: scaled once x2.96
    ("od24_motor_jaw_jam_guard_brake", "outside", 0.0070, 0.0257, 0.94,
     [E("motor_jaw_jam_guard_brake", {"torque_Nm": 5.922, "threshold_rad": 0.004, "delay_s": 0.004})]),
    # 40 N*m per m*s of the extension's integral since the stroke's start (about 3 N*m at a stroke's end)
    ("od24_wheel_stroke_dumped_metered_brake", "outside", 0.0083, 0.0243, 0.92,
     [E("wheel_stroke_dumped_metered_brake", {"coefficient_Nm_per_m_s": 40.0})]),
    # 30 N*m/rad (about +-2 N*m over the jaw's angle range), modulated +-50 % once a motor turn
    ("od24_clutch_loose_bolt_disc_pack", "outside", 0.0066, 0.0268, 0.96,
     [E("clutch_loose_bolt_disc_pack", {"stiffness_Nm_per_rad": 30.0, "modulation": 0.5, "phase_rad": 0.0})]),
    # 5 N at the section's centre 90 m from the run-in's start (about 2 s into the recording), halved 2 m either side
    # (replacing the cable reel first written here: docs/foreign_drives.md "The twenty-fourth set")
    ("od24_mass_worn_rail_section", "outside", 0.0078, 0.0236, 0.90,
     [E("mass_worn_rail_section", {"force_N": 5.0, "centre_m": 90.0, "half_width_m": 2.0})]),
    ("od24_clean_w7.3_eta0.0252_n0.93", "clean", 0.0073, 0.0252, 0.93, []),
    # 4e-6 s^4/m^2 (a_e = 500 m/s^2: about 6 % more at a1's peaks of 127 m/s^2)
    ("od24_a1_electrostatic_softening", "outside", 0.0086, 0.0247, 0.91,
     [E("a1_electrostatic_softening", {"coefficient_s4_per_m2": 4e-6})]),
    # 300 N per m of the sampled extension's shortfall below 0.295 m (up to about 4 N)
    ("od24_mass_knock_sampled_tension_clamp", "outside", 0.0068, 0.0229, 0.95,
     [E("mass_knock_sampled_tension_clamp", {"gain_N_per_m": 300.0, "reference_m": 0.295})]),
    # 2 N*m when switched in, a 10 ms period, the duty from 0 at 22.70 m/s to 1 at 22.76 m/s
    ("od24_motor_line_overspeed_brake_chopper", "outside", 0.0080, 0.0278, 0.97,
     [E("motor_line_overspeed_brake_chopper", {"torque_Nm": 2.0, "period_s": 0.01, "line_speed_m_s": 22.70,
                                               "full_duty_span_m_s": 0.06})]),
]

BENCH = _suite(BENCH_ROWS, 5000, 4.0)
WIDTH_LOOP = _suite(WIDTH_LOOP_ROWS, 6000, 4.0)
TEST = _suite(TEST_ROWS, 100, 1.2)
OUTSIDE_DEV = _suite(OUTSIDE_DEV_ROWS, 7000, 4.0)
OUTSIDE_DEV2 = _suite(OUTSIDE_DEV2_ROWS, 7300, 4.0)
OUTSIDE_DEV3 = _suite(OUTSIDE_DEV3_ROWS, 7800, 4.0)
OUTSIDE_DEV4 = _suite(OUTSIDE_DEV4_ROWS, 8000, 4.0)
OUTSIDE_DEV5 = _suite(OUTSIDE_DEV5_ROWS, 8200, 4.0)
OUTSIDE_DEV6 = _suite(OUTSIDE_DEV6_ROWS, 8400, 4.0)
OUTSIDE_DEV7 = _suite(OUTSIDE_DEV7_ROWS, 8600, 4.0)
OUTSIDE_DEV8 = _suite(OUTSIDE_DEV8_ROWS, 8800, 4.0)
OUTSIDE_DEV9 = _suite(OUTSIDE_DEV9_ROWS, 9000, 4.0)
OUTSIDE_DEV10 = _suite(OUTSIDE_DEV10_ROWS, 10000, 4.0)
OUTSIDE_DEV11 = _suite(OUTSIDE_DEV11_ROWS, 11000, 4.0)
OUTSIDE_DEV12 = _suite(OUTSIDE_DEV12_ROWS, 12000, 4.0)
OUTSIDE_DEV13 = _suite(OUTSIDE_DEV13_ROWS, 13000, 4.0)
OUTSIDE_DEV14 = _suite(OUTSIDE_DEV14_ROWS, 14000, 4.0)
OUTSIDE_DEV15 = _suite(OUTSIDE_DEV15_ROWS, 15000, 4.0)
OUTSIDE_DEV16 = _suite(OUTSIDE_DEV16_ROWS, 16000, 4.0)
OUTSIDE_DEV17 = _suite(OUTSIDE_DEV17_ROWS, 17000, 4.0)
OUTSIDE_DEV18 = _suite(OUTSIDE_DEV18_ROWS, 18000, 4.0)
OUTSIDE_DEV19 = _suite(OUTSIDE_DEV19_ROWS, 19000, 4.0)
OUTSIDE_DEV20 = _suite(OUTSIDE_DEV20_ROWS, 20000, 4.0)
OUTSIDE_DEV21 = _suite(OUTSIDE_DEV21_ROWS, 21000, 4.0)
OUTSIDE_DEV22 = _suite(OUTSIDE_DEV22_ROWS, 22000, 4.0)
OUTSIDE_DEV23 = _suite(OUTSIDE_DEV23_ROWS, 23000, 4.0)
OUTSIDE_DEV24 = _suite(OUTSIDE_DEV24_ROWS, 24000, 4.0)
SUITES = {"bench": BENCH, "widthloop": WIDTH_LOOP, "test": TEST, "outside_dev": OUTSIDE_DEV,
          "outside_dev2": OUTSIDE_DEV2, "outside_dev3": OUTSIDE_DEV3, "outside_dev4": OUTSIDE_DEV4,
          "outside_dev5": OUTSIDE_DEV5, "outside_dev6": OUTSIDE_DEV6, "outside_dev7": OUTSIDE_DEV7,
          "outside_dev8": OUTSIDE_DEV8, "outside_dev9": OUTSIDE_DEV9,
          "outside_dev10": OUTSIDE_DEV10, "outside_dev11": OUTSIDE_DEV11,
          "outside_dev12": OUTSIDE_DEV12, "outside_dev13": OUTSIDE_DEV13,
          "outside_dev14": OUTSIDE_DEV14, "outside_dev15": OUTSIDE_DEV15,
          "outside_dev16": OUTSIDE_DEV16, "outside_dev17": OUTSIDE_DEV17,
          "outside_dev18": OUTSIDE_DEV18, "outside_dev19": OUTSIDE_DEV19,
          "outside_dev20": OUTSIDE_DEV20, "outside_dev21": OUTSIDE_DEV21,
          "outside_dev22": OUTSIDE_DEV22, "outside_dev23": OUTSIDE_DEV23,
          "outside_dev24": OUTSIDE_DEV24}


# The sealed halves: each made on first use from its own module's rows (foreign_drives.<name>.suite_rows(), so that
# nothing of it is read before it is asked for), 4 s recordings, seeds from this number on in its rows' order
SEALED_FIRST_SEED = {
    "outside_sealed": 7100,
    "outside_sealed2": 7400,
    "outside_sealed3": 7900,
    "outside_sealed4": 8100,
    "outside_sealed5": 8300,
    "outside_sealed6": 8500,
    "outside_sealed7": 8700,
    "outside_sealed8": 8900,
    "outside_sealed9": 9100,
    "outside_sealed10": 10100,
    "outside_sealed11": 11100,
    "outside_sealed12": 12100,
    "outside_sealed13": 13100,
    "outside_sealed14": 14100,
    "outside_sealed15": 15100,
    "outside_sealed16": 16100,
    "outside_sealed17": 17100,
    "outside_sealed18": 18100,
    "outside_sealed19": 19100,
    "outside_sealed20": 20100,
    "outside_sealed21": 21100,
    "outside_sealed22": 22100,
    "outside_sealed23": 23100,
    "outside_sealed24": 24100,
}

SUITE_NAMES = tuple(SUITES) + tuple(SEALED_FIRST_SEED)


def _sealed(name: str) -> list:
    """A sealed half's suite, made from foreign_drives.<name> on first use (its rows live there)."""
    rows = importlib.import_module(f".{name}", __package__).suite_rows()
    return _suite(rows, SEALED_FIRST_SEED[name], 4.0)


def suite(name: str) -> list:
    if name in SEALED_FIRST_SEED:
        return _sealed(name)
    if name not in SUITES:
        raise ValueError(f"unknown suite {name!r}; allowed: {', '.join(SUITE_NAMES)}")
    return list(SUITES[name])
