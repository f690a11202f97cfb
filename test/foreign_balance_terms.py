"""What an outside mechanism adds to each balance of a foreign recording (noise off), from its internal signals: the
balance's other terms subtracted (test_foreign_drives_outside.py, outside2.py and outside3.py check each mechanism's law so)."""
import numpy as np

from foreign_drives import constants as C
from foreign_drives.drive import pulse_indicator

W = C.WHEEL_RADIUS_M
T_B = C.BASE_TORQUE_NM
J1 = C.MOTOR_INERTIA_KGM2
J2 = C.WHEEL_INERTIA_KGM2


def motor_term_Nm(rec):
    """T_x on the motor's load: J1 dOmega1/dt = T_b t_e - T_c - T_b*pulse - T_x (noise off)."""
    i = rec.internal
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    pulse = i["pulse_amplitude_pu"] * pulse_indicator(t, rec.spec.pulse_first_s)
    return T_B * i["te_pu"] - i["clutch_torque_Nm"] - J1 * i["a1_physical"] / W - T_B * pulse


def wheel_term_Nm(rec):
    i = rec.internal
    return J2 * i["wheel_acceleration"] - i["clutch_torque_Nm"] + W * i["rim_force_N"]


def mass_term_N(rec):
    i = rec.internal
    return C.MASS_KG * i["a2_physical"] - i["rim_force_N"] + C.WORKING_RESISTANCE_N


def contact_law_Nm(rec):
    """The contact law's own torque (SPEC: k_c*p + d_c*p', far side negative, 0 in the gap) from the exact angle
    difference and the speeds (no shaft hub: the rate of D is Omega1 - Omega2): what the clutch torque is without an
    outside clutch term."""
    from foreign_drives import kernel as K
    i = rec.internal
    d, dd, mode = i["jaw_angle_difference"], rec.signals["omega1"] - rec.signals["omega2"], i["mode"]
    beta = i["parameters"][K.P_BETA]
    k, c = C.CONTACT_STIFFNESS_NM_PER_RAD, C.CONTACT_DAMPING_NMS_PER_RAD
    return np.where(mode > 0, k * (d - beta) + c * dd, np.where(mode < 0, -(k * (-d - beta) - c * dd), 0.0))
