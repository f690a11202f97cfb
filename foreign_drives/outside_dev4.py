"""Outside mechanisms, fourth DEVELOPMENT half (issue 31 part 4, set 4): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first three sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2`, :mod:`outside_sealed2`, :mod:`outside_dev3`, :mod:`outside_sealed3`)
have, with their laws in the open. The fourth sealed half is :mod:`outside_sealed4`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed4` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 sensor, 14 wheel torque).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength was set
by one quick simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the STROKE COUNT (a sub-harmonic of the pulse train): a progressive die whose piercing
   station works on every N-th part only; an extra load T during the strokes k = m (mod N), k the stroke's number;
3. wheel torque x the wheel speed through a ONE-WAY MEMORY: a feed roll's flywheel on the wheel shaft behind an
   overrunning (sprag) clutch with a compliant coupling; it is dragged up, -c*(Omega2 - w_f), whenever the wheel runs
   faster than it, and coasts down on its bearing drag otherwise (a hidden speed w_f that rises fast and falls slowly);
5. clutch torque x the penetration through a RELAXATION (a memory of the contact): the jaw's elastomer insert is
   viscoelastic (a standard linear solid); beyond the contact law a Maxwell branch k_m*(p - q) acts in contact, q the
   branch's relaxed penetration, dq/dt = (p - q)/tau;
7. mass force x the spring extension through a ONE-SHOT TIMER: a proximity switch on the spring's bracket fires a
   pneumatic rail clamp on the carriage for a fixed time each time the extension rises through a set value (a PLC
   one-shot, not retriggered while it runs): -F*sign(v) for T_h after the trigger;
9. a1 sensor x a1's own RATE: the rotating a1 channel passes an isolation amplifier whose output slews at most S
   (a slew-rate limit: a memory of the signal's last value, not a filter of fixed dynamics);
11. a1 sensor x the MOTOR ANGLE as a gate on a HOLD: a1's rotating telemetry loses its radio link while its antenna
    passes behind the motor frame, once per revolution, over an angle window; the receiver holds the last value;
13. mass force x the mass speed SAMPLED and DELAYED: a linear motor on the carriage holds the carriage's speed under a
    digital speed loop: it samples v every scan and applies, some scans later, -K*(v_sampled - v_ref), held between
    scans.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0). Memory elements (the one-way flywheel, the Maxwell branch, the one-shot, the sampled loop; one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py
"memory"), like the third set's relay; they act in the run with every term, from the run-in's start (2 s before
sample 0), not in the settled start's period map.
"""
