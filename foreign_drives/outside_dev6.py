"""Outside mechanisms, sixth DEVELOPMENT half (issue 31 part 4, set 6): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first five sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev5`, :mod:`outside_sealed5`) have, with their laws in
the open. The sixth sealed half is :mod:`outside_sealed6`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed6` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 motor load moment, 14 mass
force). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength
is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a STICK-SLIP coupling to a hidden inertia: a brake disc (or a fan)
   on the motor's free shaft end sits on a friction (slip) hub that has loosened; it turns with the shaft as long as
   the torque to accelerate it, J_f*dOmega1/dt, stays below the hub's slip torque T_s, and slips beyond (at the jaw's
   impacts), passing +-T_s until it has caught up: a hidden degree of freedom through a dry-friction coupling;
3. wheel torque x the wheel speed through a hidden body in a GAP (gear rattle): an unloaded idler gear (the drive of a
   tacho-generator, an encoder's pinion) meshes with a gear on the wheel shaft with backlash +-g; a bearing drag keeps
   it on the driving flank while the wheel runs steadily, and whenever the wheel decelerates faster than the drag can
   slow the idler, it crosses the gap and strikes the other flank: an intermittent contact elsewhere in the train;
5. clutch torque x the contact law through a SATURATION: a ball-detent torque limiter in the jaw's hub; above T_lim
   the balls ride up their ramps and the coupling passes T_lim whatever the penetration, springing back as the torque
   falls: the contact torque capped, sign(T_c)*min(|T_c|, T_lim);
7. mass force x the STROKE COUNT accumulated and reset: each stroke drops a finished part onto a tray on the carriage
   and a sweeper empties the tray every N strokes; the parts' weight loads the carriage's rail with friction, a force
   against the motion growing by F_p with each part, -F_p*((k - k_0) mod N)*sign(v), k the stroke's number (a staircase
   with a periodic reset, a discrete event count);
9. a2 sensor x the SIGN of a2 (a bilinear gain): a2's accelerometer has a cracked suspension spring on one side of its
   proof mass, so its gain differs for the two directions, a2 = a*(1 + g) for a > 0 and a*(1 - g) for a < 0, i.e.
   a2 = a + g*|a|: an even-order, memoryless distortion with a kink at zero;
11. a2 sensor x its own OVERLOADS through a dead time: a2's sigma-delta module detects an overload when |a| exceeds its
    range A and resets its digital filter: its output is 0 while the input is over range and for T_r after it
    returns (a recovery time, retriggered by every overload sample);
13. wheel torque x the wheel speed through a PWM actuator: a chopper drives the wheel's eddy-current brake at a fixed
    carrier period T_p; at each carrier period's start the PLC samples the wheel speed and sets the duty
    d = clip((Omega2_s - Omega_0)/dOmega, 0, 1); the brake is then fully on (-T) for d*T_p of the period and off for
    the rest (a quantised, time-gated actuator, not a proportional one).

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth and fifth sets.
"""
