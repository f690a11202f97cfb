"""Outside mechanisms, fifth DEVELOPMENT half (issue 31 part 4, set 5): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first four sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2`, :mod:`outside_sealed2`, :mod:`outside_dev3`, :mod:`outside_sealed3`,
:mod:`outside_dev4`, :mod:`outside_sealed4`) have, with their laws in the open. The fifth sealed half is
:mod:`outside_sealed5`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed5` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 motor load moment, 14 wheel
torque). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength
is set by one quick simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a PLAY (a rate-independent hysteresis, a backlash operator): a
   flyball governor on the motor shaft sets a brake band through a linkage with play; the linkage's position m
   follows Omega1 only once Omega1 has moved more than h away from it, m = min(max(m, Omega1 - h), Omega1 + h), and the
   band loads the motor with K*max(0, m - Omega_0);
3. wheel torque x a PRODUCT of the unwrapped wheel angle and the spring extension: the spring's cable winds onto the
   wheel's drum in layers, so its lever arm grows by dr per turn; the spring's force k*z acts on the growing arm,
   -k*z*dr*theta2/(2*pi) beside the nominal r*k*z (theta2 unwrapped from the run-in's start);
5. clutch torque x the contact law TIMES the wheel angle (an amplitude modulation of the contact): the jaw coupling's
   hub runs out on the wheel shaft, so the contact's lever arm and with it the torque a given penetration passes vary
   once per revolution, T_c*g*sin(alpha2 + phi);
7. mass force x a HIDDEN RESONATOR driven by the mass speed: a tuned vibration absorber (an auxiliary mass on a spring
   and damper) bolted to the carriage; its relative displacement d and speed obey d'' = -w_a^2*d - 2*zeta*w_a*d' -
   dv/dt, and it pushes the carriage with m_a*(w_a^2*d + 2*zeta*w_a*d') (advanced once per 0.2 ms);
9. a2 sensor x TIME and a2's own PAST (a tare): a2's data-acquisition module auto-zeroes every T_z seconds: at each
   tare it takes the mean of its input over the W seconds before as its new zero, and subtracts it until the next;
11. clutch torque x a THERMAL MEMORY of the power the contact dissipates: the jaw's elastomer insert heats with the
   power P = |T_c*D'| its impacts dissipate and cools with tau; it softens as it heats, the contact torque times
   (1 - g*theta), theta' = P - theta/tau (theta the heat held, J; advanced once per 0.2 ms);
13. a2 sensor x a2's own value through a STUCK ADC BIT: a2's I/O module digitises it with an ADC of N bits over +-R
   whose bit b is stuck at 1 (a failed line): every code has that bit set, a non-monotone, periodic error in the
   signal's amplitude.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0). Memory elements (the play, the resonator, the insert's heat; one per recording) are advanced once
per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"), as in the fourth set.
"""
