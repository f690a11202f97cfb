"""Outside mechanisms, eighth SEALED half (issue 31 part 4, set 8).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed8``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first seven sets
nor the eighth development half (:mod:`outside_dev8`) has, and the suite's rows (seeds 8900+). The split rule is in
:mod:`outside_dev8` (written as one list of fourteen; the even numbers are here; 8, 10, 12 with a memory, 2, 4, 6, 14
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed8")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed as a CONSTANT POWER: a generator on the motor's free shaft end feeds a
   regulated consumer (a DC bus with a constant-power load): T = P/Omega1 (a hyperbolic law: the load falls as the
   speed rises, a negative slope);
4. wheel torque x the wheel angle as a SAWTOOTH: a snail (drop) cam on the wheel shaft winds up a knock-out spring
   over each turn and lets it snap at the cam's drop: -T*((theta2 - phi) mod 2*pi)/(2*pi), theta2 the wheel angle
   unwrapped from the run-in's start (a torque rising linearly over a turn and falling at once: not a harmonic);
6. clutch torque x the contact torque GATED by the motor angle: one of the n jaw teeth on the motor's half is cracked
   and softer; while it is the one engaged (one n-th of each motor turn, from the motor angle phi on) the contact passes
   (1 - g) of its torque: -g*T_c*[(alpha1 - phi) mod 2*pi < 2*pi/n] (a tooth fault: the contact modulated by a
   rectangular window of the angle, once per turn);
8. mass force x the load pulse through a DRAINING TANK: each stroke's coolant runs into a tray on the carriage at a
   rate q while the pulse is on and drains through an orifice at c*sqrt(V) (Torricelli); the water's weight presses
   the carriage onto its rail: a friction -mu_g*V against its (forward) motion, V' = q*pulse - c*sqrt(V) (advanced
   every 0.2 ms from V = 0 at the run-in's start: a nonlinear store, not a linear lag);
10. a1 sensor x a1's own magnitude through an AUTO-RANGING with hysteresis: a1's module switches to its coarse range
    at the first sample with |a| > R_hi and back to its fine range at the first with |a| < R_lo; in the coarse range
    the reading has a gain error g and steps q: y = q*round((1 + g)*a/q), in the fine range y = a (the reading's
    error switched by the signal's own history);
12. motor load moment x the motor speed through a THREE-POINT STEP CONTROLLER: a motorised throttle on a pump on the
    motor's shaft end is driven by a step controller: while Omega1 has been above Omega_ref + b (below Omega_ref - b)
    for T_s since the last step, the throttle opens (closes) one step, within 0..N steps; the pump loads the motor with
    K per step open (scanned every 0.2 ms: a stepping integrator with a dead band);
14. mass force x the mass speed through an EDDY-BRAKE CHARACTERISTIC: a linear eddy-current rail brake on the carriage
    at its real speed characteristic, -2*F_m*(v/v_c)/(1 + (v/v_c)^2): a force that peaks at the critical speed v_c and
    FALLS above it (the carriage runs above v_c: a negative slope, not a viscous drag).
"""
