"""The model-form tolerance: how far a real drive may differ from its model without any effect missing.

A real drive never matches its model exactly: its nominal values are known to within a tolerance (a mass weighed,
an inertia from a drawing, an elastomer jaw's stiffness from a catalogue), and its laws are written differently
from the model's (another friction curve, another contact law). The null hypothesis of the consistency test
(consistency.py) allows for that: the model's prediction may be off by the spread of its nominal parameters,
N(0, sum_j (J_j sigma_j)(J_j sigma_j)'), J_j the prediction's derivative by parameter j (the screening's
secants, common random numbers) and sigma_j its plausible error (NOMINAL_SIGMA, config/workbench.yaml has the
reasons). An effect must exceed that to be discovered. The width is not in it: it is the measurand.
"""
from __future__ import annotations

import numpy as np

# plausible 1-sigma error of each nominal value of a drive's model, in the parameter's unit (reasons:
# config/workbench.yaml "tolerance"); keys are the catalogue parameters that change the nominal value
NOMINAL_SIGMA = {
    "load_mass_drift.relative_change": 0.02,           # a mass weighed or taken from a drawing: +-2 %
    "wheel_inertia_drift.relative_change": 0.05,       # an inertia from a drawing or a catalogue: +-5 %
    "spring_stiffness_drift.relative_change": 0.05,    # a spring's rate: +-5 % (spring makers' grade tolerance)
    "absorber_consistency_drift.relative_change": 0.05,  # a fluid's consistency at the operating temperature: +-5 %
    "absorber_flow_index_drift.change": 0.005,         # its flow index: +-0.005
    "working_resistance_drift.relative_change": 0.05,  # the process force: +-5 %
    "pulse_amplitude_drift.relative_change": 0.02,     # the duty cycle's load: +-2 %
    "rotor_resistance_drift.relative_change": 0.04,    # the rotor's resistance at its unknown temperature: +-10 K
    "supply_voltage_drift.relative_change": 0.02,      # the supply voltage at the motor's terminals: +-2 %
    "clutch_contact_stiffness.relative_change": 0.05,  # an elastomer jaw's stiffness: +-5 %
    "clutch_contact_damping.relative_change": 0.10,    # its damping: +-10 %
    "accelerometer_gain.a1_relative_change": 0.02,     # a calibrated accelerometer's sensitivity: +-2 %
    "accelerometer_gain.a2_relative_change": 0.02,
}

# The spread above enters the consistency test's covariance x SCALE. Measured (docs/workbench.md "Model-form
# tolerance"): at SCALE 1 the 4 s recording's precision (a 3 % mass error gives T^2 41 against 15) is swamped -- a +30 %
# mass read T^2 3.8 -- so the test carries none of it (0), and the spread is used where it belongs: a fitted change of a
# nominal value must exceed TOLERANCE_FACTOR (decisions.py) x its sigma to be a discovery (beyond_tolerance), which
# stopped a +1.5 % eta_k from being named as a second effect beside a foreign friction law.
SCALE = 0.0


def sigma_of(candidate) -> np.ndarray:
    """Per fitted parameter of a candidate (plant_adapter.CandidateEffect): its nominal tolerance (0: none)."""
    return np.array([NOMINAL_SIGMA.get(p.key, 0.0) for p in candidate.parameters])


SPECTRAL_SHAPE_SIGMA = 0.1   # ln(power ratio of adjacent bands): the model's spectral shape above the denoising's
                             # edge is trusted to ~10 % per band ratio (measured: a foreign drive's physical a2, before
                             # its sensor, differs from ours by 0.05-0.1 in these ratios at eta_k 0.019; the features'
                             # event-to-event noise over 16 events is ~0.02-0.07)


SPEED_SIGMA_RAD_S = 0.3      # the motor's mean speed: its slip moves with the rotor's temperature (r_r +0.4 %/K: +-10 K
                             # is +-4 % of the 3.6 % slip, +-0.2 rad/s) and the supply's frequency (+-0.1 %: 0.15 rad/s);
                             # measured: a foreign clean drive's mean speed differs from ours by up to ~0.05 rad/s


def directions(problem, jacobians: dict, by_name: dict) -> np.ndarray:
    """(N, m): the prediction-space directions of the model-form tolerance: the nominal parameters' spread,
    J_j * sigma_j from the screening Jacobians (``jacobians``: {candidate name: (N, k)}; x SCALE), an independent discrepancy of SPECTRAL_SHAPE_SIGMA per
    spectral-shape feature, and SPEED_SIGMA_RAD_S on the motor's mean speed."""
    n = problem.target_vec.size
    cols = []
    for name, jacobian in jacobians.items():
        sig = sigma_of(by_name[name]) * SCALE
        for i, s in enumerate(sig):
            if s > 0:
                cols.append(jacobian[:, i] * s)
    sl = problem.spectral_slice
    for i in range(sl.start, sl.stop):
        c = np.zeros(n)
        c[i] = problem.ws[i - sl.start] * SPECTRAL_SHAPE_SIGMA
        cols.append(c)
    for j, name in enumerate(getattr(problem, "dc_names", ())):
        if name == "omega1":
            c = np.zeros(n)
            c[problem.dc_slice.start + j] = problem.wdc[j] * SPEED_SIGMA_RAD_S
            cols.append(c)
    return np.stack(cols, axis=1) if cols else np.zeros((n, 0))


def beyond_tolerance(fit, candidate, factor: float = 2.0) -> bool:
    """A fitted candidate's change exceeds ``factor`` x its nominal tolerance in at least one parameter (always
    True for a parameter without a tolerance: an effect the model lacks altogether)."""
    sig = sigma_of(candidate)
    d = np.abs(np.asarray(fit.values) - np.asarray(fit.nominal))
    return bool(np.any((sig == 0) | (d > factor * sig)))


def measurand_form_sigma(problem, jacobians: dict, by_name: dict, measurand_column: np.ndarray) -> float:
    """The model-form tolerance of a measurand fitted alone (the backlash width) [its unit]: how far the fitted value
    moves when the drive's nominal values are off by their sigma (NOMINAL_SIGMA; the whole sigma, not x SCALE: the
    width takes up what it can of a nominal error) and the model's spectral shape and mean speed by theirs. Per
    tolerance direction d: the shift (j'd)/(j'j) of the linear fit of the measurand's column j (projected); the
    directions are independent: the root of the sum of squares. ``jacobians``: the screening's, {candidate name:
    (N, k)}; ``measurand_column``: the measurand's Jacobian column in the prediction space."""
    j = problem.project(np.asarray(measurand_column, dtype=float))
    jj = float(j @ j)
    if not jj > 0:
        return float("nan")
    cols = []
    for name, jacobian in jacobians.items():
        for i, s in enumerate(sigma_of(by_name[name])):
            if s > 0:
                cols.append(jacobian[:, i] * s)
    shifts = [float(j @ problem.project(c)) / jj for c in cols]
    rest = directions(problem, {}, by_name)        # the spectral shape's and the mean speed's (no nominal spread)
    if rest.shape[1]:
        shifts += list((j @ problem.project(rest)) / jj)
    return float(np.sqrt(np.sum(np.square(shifts))))
