"""Outside mechanisms, twelfth SEALED half (issue 31 part 4, set 12).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed12``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first eleven sets
nor the twelfth development half (:mod:`outside_dev12`) has, and the suite's rows (seeds 12100+). The split rule is in
:mod:`outside_dev12` (written as one list of fourteen; the even numbers are here; 2, 6, 8, 12 with a memory, 4, 10, 14
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed12")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a RATE-LIMITED FOLLOWER: a conveyor on the motor's shaft end through a
   viscous coupling; the conveyor's own drive follows the line speed with a ramp limit R (its speed m moves towards
   Omega1 by at most R*dt every 0.2 ms, m = Omega1 at the run-in's start), the motor loaded with c*(Omega1 - m) (a
   load that appears only while the motor's speed changes faster than the follower may: the sixth set's rate limiter
   acts on the spring's extension and the mass);
4. wheel torque x the wheel speed through a STAIRCASE of stages: a multi-stage retarder on the wheel whose speed switch
   adds one stage of T per step of Omega_s above Omega_0: -T*floor((Omega2 - Omega_0)/Omega_s) (0 below Omega_0) (a
   quantised law of the speed itself: the fifth set's stairs act on a sampled tacho on the motor);
6. clutch torque x the slip speed through a DEAD TIME: an electronically slip-controlled eddy-current coupling beside
   the jaw, whose controller reads the two shafts' speeds over a fieldbus: c*(Omega1 - Omega2)(t - T_d), the slip
   sampled every 0.2 ms and applied T_d later (a damping of the slip that acts on its past: the earlier clutch terms
   read the slip, the angle or the contact now);
8. mass force x the mass speed INTEGRATED SINCE EACH STROKE'S START: a return spring on the carriage hooked at each
   stroke's start: its extension is the distance the carriage travelled since the latest pulse's first 0.2 ms scan
   (s = integral of v, reset to 0 there), the carriage pulled back with -k*s (the seventh set integrates the motor
   speed since the stroke for a motor term);
10. a1 sensor x a1 itself through an EVEN-ORDER distortion: a1's piezo element and its preamplifier bend the
    characteristic quadratically: y = x + x^2/a_q (a second harmonic of the signal and a shift of its mean: the
    earlier sensor nonlinearities are odd, bilinear, a dead zone or quantisations);
12. a2 sensor x a2's own last sample through a PRE-EMPHASIS: a2's digital transmitter boosts the high frequencies
    before sending and the receiver never undoes it: y[n] = (x[n] - k*x[n-1])/(1 - k) (a first-order FIR high shelf,
    unity gain at DC);
14. clutch torque x the slip speed GATED by the motor speed: a viscous torsional damper beside the jaw bypassed by a
    centrifugal valve above Omega_v: c*(Omega1 - Omega2)*(1 - S((Omega1 - Omega_v)/w)), S(q) = (1 + tanh(q))/2 (a
    damping switched off by the speed).
"""
