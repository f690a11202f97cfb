"""Outside mechanisms, eleventh SEALED half (issue 31 part 4, set 11).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed11``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first ten sets
nor the eleventh development half (:mod:`outside_dev11`) has, and the suite's rows (seeds 11100+). The split rule is in
:mod:`outside_dev11` (written as one list of fourteen; the even numbers are here; 2, 6, 8, 14 with a memory, 4, 10, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed11")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a MAGNETIC COUPLING to a HIDDEN ROTOR (a periodic, pole-slipping
   spring): an auxiliary pump hangs on the motor's shaft end behind a permanent-magnet (canned) coupling of n pole pairs
   and pull-out torque T_m; its rotor (inertia J_r, viscous load c_r) follows through the magnets' torque
   T_m*sin(n*phi), phi the angle of the motor's half ahead of the rotor: phi' = Omega1 - w_r, J_r*w_r' = T_m*sin(n*phi) -
   c_r*w_r, the motor loaded with T_m*sin(n*phi) (advanced every 0.2 ms; w_r = Omega1 and n*phi = asin(c_r*Omega1/T_m)
   at the run-in's start) (a hidden degree of freedom through a sinusoidal spring that slips a pole when overloaded:
   the fourth set's belts are a viscous lag, the sixth set's hub a dry friction, the fifth set's absorber a linear
   spring);
4. wheel torque x the jaw's CONTACT TORQUE beyond a PRELOAD: a torque-sensing (ball-ramp) brake in the wheel's hub; the
   torque the jaw passes on its drive face pushes balls up one-way ramps against a preload spring and presses a brake
   pack on the wheel: -k*max(0, T_c - T_0), T_c the contact torque (+ motor to wheel) (a brake set by the transmitted
   torque: the third set's thrust bearing puts |T_c| on the motor, without a preload);
6. clutch torque x the slip speed TIMES a FILL LEVEL that ramps with the pulse: a fill-controlled fluid coupling beside
   the jaw; the press's valve fills it at a fixed rate while the pulse is on and it drains at another rate otherwise:
   c*f*(Omega1 - Omega2), f += dt/T_fill while the pulse is on, f -= dt/T_drain otherwise, f clamped to [0, 1] (every
   0.2 ms, f = 0 at the run-in's start) (a clamped integrator: straight ramps between hard limits, not an exponential
   lag);
8. mass force x the mass speed through RATE-AND-STATE FRICTION: the carriage's polymer slideway follows the Dieterich-
   Ruina law: -(a*ln(v/v_0) + b*ln(v_0*theta/D_c)), theta' = 1 - v*theta/D_c (the contact's age: over each 0.2 ms scan
   theta -> D_c/v + (theta - D_c/v)*exp(-v*dt/D_c); theta = D_c/v at the run-in's start) (a friction with a state
   that evolves over a slip distance D_c: a speed step gives a direct jump a*ln, then a relaxation to (a - b)*ln over
   D_c of travel: neither a viscous, a Coulomb, nor a lag of the speed);
10. a1 sensor x a1 through RANDOM BIT ERRORS: a1's rotating telemetry has no error check; a sample's 16-bit two's-
    complement code c = clip(round(32767*a/R), -32768, 32767) has, at a rate p, one bit b (of 16, at random) flipped: y
    = a + (c' - c)*R/32767 for a corrupted sample, y = a otherwise (u_n, b_n from numpy's default_rng(seed).random((N,
    2)) row n, n the sample from the pre-roll's first; corrupted where u_n < p, b = floor(16*v_n)) (sparse impulsive
    errors whose size is a power of two of the code step: not a noise, not a quantiser);
12. a2 sensor x a2 through a STITCHED DUAL-RANGE: a2's module has two ADCs, a fine one up to R and a coarse one above,
    stitched with a gain mismatch g: y = a for |a| <= R, sign(a)*(R + (1 + g)*(|a| - R)) beyond (a kink in the gain at
    +-R: not a saturation, not a range switch with a memory);
14. clutch torque x the jaw's angle difference through a BISTABLE (over-centre) TOGGLE SPRING: a snap spring between the
    jaw halves flips over its centre when the angle difference D passes +d (towards the drive face) and back when it
    passes -d (towards the far face), and pushes the halves towards the face they last went past: T*(2*s - 1), s -> 1
    when D > d, s -> 0 when D < -d (scanned every 0.2 ms; s = 0 at the run-in's start) (a two-state, rate-independent
    hysteresis of the relative angle with a jump: the sixth set's Dahl ring is smooth, the seventh set's magnets
    memoryless).
"""
