"""Outside mechanisms, seventh SEALED half (issue 31 part 4, set 7).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed7``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first six sets
nor the seventh development half (:mod:`outside_dev7`) has, and the suite's rows (seeds 8700+). The split rule is in
:mod:`outside_dev7` (written as one list of fourteen; the even numbers are here; 2, 6, 10 with a memory, 4, 8, 12, 14
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed7")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a THERMAL INTEGRATOR: the motor's bearings start the shift cold; their
   grease's drag T_0*exp(-theta/theta_c)*tanh(Omega1/1 rad/s) falls as they warm, theta' = h*Omega1^2 - theta/tau
   (theta = 0 at the run-in's start, scanned every 0.2 ms): a drift within the record driven by the speed's history;
4. wheel torque x time at a SWEEPING frequency: a neighbouring machine (a centrifuge) runs up during the recording;
   its unbalance rocks the common frame and the wheel feels it as a torque A*sin(2*pi*(f0*t + k*t^2/2) + phi), t from
   sample 0 (a chirp: non-stationary, locked to no shaft and to no fixed frequency);
6. clutch torque x the penetration through a PEAK DETECTOR: the jaw's elastomer insert softens with the deepest
   penetration it has had lately (a Mullins-type stress softening that recovers): T += -k_s*p_peak*p in contact, p
   the penetration, p_peak its peak held and decaying with a time constant tau (scanned every 0.2 ms);
8. mass force x the mass speed TIMES the spring extension squared: an eddy-current damper's magnet sits on the spring's
   bracket; as the spring stretches the magnet closes on the rail: F = -c*(z/z_ref)^2*v (a damping whose coefficient
   the spring's extension sets);
10. a1 sensor x a1's own ENVELOPE: a1's rotating telemetry has an automatic gain control: y = a/(1 + e/A), e a
    first-order lag (tau) of |a| (a compressor with a memory: slow gain changes, not an instantaneous saturation);
12. a2 sensor x a2 TIMES a fixed-frequency modulation: the module's voltage reference ripples at f_r (its switch-mode
    supply's beat), so its gain does: y = a*(1 + g*sin(2*pi*f_r*t + phi)) (an amplitude modulation, not an additive
    hum);
14. mass force x the load pulse TIMES the wheel angle: during each stroke a hold-down roller presses the carriage onto
    its rail; the roller is driven from the wheel shaft and runs eccentric, so its pressing force, and with it the
    rail friction, varies once per wheel turn: -F*pulse*(1 + e*sin(alpha2 + phi))*tanh(v/0.01 m/s).
"""
