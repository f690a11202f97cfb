"""Outside mechanisms, thirteenth SEALED half (issue 31 part 4, set 13).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed13``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first twelve sets
nor the thirteenth development half (:mod:`outside_dev13`) has, and the suite's rows (seeds 13100+). The split rule is
in :mod:`outside_dev13` (written as one list of fourteen; the even numbers are here; 2, 4, 6, 8, 10 with a memory, 12,
14 memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed13")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a TUNED TORSIONAL ABSORBER: a ring (inertia J_a) on a rubber spring and
   damper on the motor's free shaft end, tuned to w_a with damping ratio zeta: its angle d relative to the shaft obeys
   d'' = -w_a^2*d - 2*zeta*w_a*d' - dOmega1/dt (at rest at the run-in's start), the motor loaded with
   -J_a*(w_a^2*d + 2*zeta*w_a*d') (a hidden spring-coupled inertia on the motor: the fourth set's flywheel is coupled
   viscously, the sixth set's by friction, the eleventh set's magnetically; the fifth set's absorber is on the mass);
4. wheel torque x the wheel speed through an IMPULSE RELAY: an overspeed switch on the wheel's shaft pulses a latching
   (impulse) relay that switches a brake: each time Omega2 rises past Omega_on (re-armed below Omega_off) the brake
   toggles on or off, -T while on (off at the run-in's start) (a brake that alternates between overspeeds: the tenth
   set's impulse relay reads the spring's extension for the mass);
6. clutch torque x the slip speed through an ON-DELAY: a slip monitor engages an electromagnetic coupling beside the
   jaw once the motor has overrun the wheel by more than s_on for longer than T_on (reset at once below): c*(Omega1 -
   Omega2) while engaged (a damping of the slip switched by its own persistence: the seventh set's on-delay reads the
   mass speed for a rail brake);
8. mass force x the mass speed through a FRICTION-HELD PAYLOAD: a coil of strip (mass m_p) lies on the carriage's bed
   and is carried along by friction up to mu*m_p*g; a larger acceleration lets it slide: the carriage feels the force
   that brings the payload's speed to its own over each 0.2 ms scan, passed whole within +-F_s, else +-F_s (the payload
   slides), reversed in sign (a hidden mass on a friction contact with the carriage: the sixth set's slip hub is on the
   motor, its tow chain a slack, not a friction);
10. a1 sensor x a1's own past through an INTEGRATING ADC WITH HOLD: a1's module integrates its input over blocks of N
    samples (a dual-slope converter) and holds each block's mean through the next block: y over block k = the mean of
    x over block k - 1 (blocks counted from the pre-roll's first sample; x[0] before it) (a decimation with an average
    and a one-block latency; the fifth set's undersampling has no average, the ninth set's smoothing no hold);
12. a2 sensor x a2 itself through an ASYMMETRIC HARD CLIP: a2's amplifier runs from a single supply with its
    zero off centre, so it rails at +R_p and -R_n, R_p != R_n: y = clip(x, -R_n, R_p) (a hard limit, different each
    side: the second set's a1 saturation is soft and symmetric, the eighth set's wrap-around wraps, the eleventh set's
    dual range stitches);
14. mass force x the SPRING EXTENSION, spatially periodic: the spring's cable carries crimped ferrules every lambda
    that pass a spring-loaded detent roller on the carriage's cable guide: F*sin(2*pi*z/lambda + phi), z the spring's
    extension (a force periodic in the extension: the fifth set's rail is periodic in the carriage's position, the
    eighth set's detent in the jaw's angle).
"""
