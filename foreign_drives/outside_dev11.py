"""Outside mechanisms, eleventh DEVELOPMENT half (issue 31 part 4, set 11): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first ten sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev10`, :mod:`outside_sealed10`) have, with their laws in
the open. The eleventh sealed half is :mod:`outside_sealed11`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, sensor, wheel torque, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed11` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 clutch torque). About half of the fourteen are plain memoryless laws of new kinds, half have a
memory or a limit of their own (here: 1, 5, 7, 13 memoryless; 3, 9, 11 with a memory). Written before any diagnose,
analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation against the
clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the WHEEL speed beyond a limit (a CROSS-SHAFT governor): a runaway guard; a centrifugal governor
   on the wheel shaft pulls, by a rod, a band brake on the motor's shaft when the load side overspeeds: K*max(0, Omega2 -
   Omega_0) on the motor's load (the motor braked by the other shaft's speed: every earlier motor-load term reads the
   motor's own states, the pulse, the spring, the carriage or the contact torque, none the wheel speed);
3. wheel torque x the wheel speed through an OFF-DELAY timer: an overspeed brake on the wheel that a PLC switches on
   whenever Omega2 exceeds Omega_trip (scanned every 0.2 ms) and releases only once Omega2 has stayed at or below it for
   T_off (a TOF timer, retriggered by every scan above): -T while on (the seventh set's guard is an ON-delay, which
   delays the switching on; this one holds the brake on after the cause has gone);
5. clutch torque x the jaw's slip speed, ONE-WAY: an overrunning (sprag) clutch in series with a viscous coupling,
   beside the jaw: it passes c*max(0, Omega1 - Omega2) from the motor to the wheel while the motor half runs faster and
   freewheels while the wheel half overruns (a half-wave law of the slip: the first set's gap drag is two-way, the
   second set's stroke coupling is switched by the pulse);
7. mass force x the mass speed through a DEAD-BAND (three-level) switch, memoryless: a linear drive on the carriage
   under a two-contact speed switch: it pushes the carriage with +F below v_ref - b, brakes it with -F above v_ref + b
   and does nothing in between, each contact's edge smoothed over w: -F*(S((v - v_ref - b)/w) + S((v - v_ref + b)/w) -
   1), S(q) = (1 + tanh(q))/2 (a ternary law of the speed: neither a threshold's excess nor a relay with a memory);
9. a2 sensor x a2's own past through a MAINS NOTCH FILTER: a2's data-acquisition module has its 50 Hz notch switched on:
   a second-order IIR notch at f_0 of quality Q (y'' + (w0/Q)*y' + w0^2*y = a'' + w0^2*a, discretised as
   scipy.signal.iirnotch at the recorder's 50 kHz), started at rest on the pre-roll's first sample (a band-stop: the
   catalogue's sensor filters are low-passes, the third set's AC coupling is a high-pass);
11. mass force x the spring extension's change SINCE EACH STROKE'S START through a POLYTROPIC gas law: a pneumatic
    cushion cylinder between the carriage and the spring's cable; the press's valve closes its ports at each stroke's
    start, trapping its air column of length L0, so until the next stroke it pushes the carriage along x with F0*((L0/(L0 -
    dz))^gamma - 1), dz = z - z_k, z_k the extension at the first 0.2 ms scan of the latest pulse (a stiffness whose
    zero is re-set by every stroke, hardening as the air is squeezed: the fifth set's dancer holds a sample of z, not a
    spring from it);
13. wheel torque x the time as a RANDOM STAIRCASE: the uncoiler upstream hands the strip's tension down through its own
    controller, which moves to a new level at each of its updates, every T_s seconds: T*u_k, k = floor((t - t_0)/T_s),
    u_k pseudo-random in [-1, 1) of k and a seed (a piecewise-constant random torque locked to no shaft, no stroke and
    no event of this drive: the tenth set's chain pattern is locked to the wheel angle, the sixth set's blanks to the
    stroke count, the fourth set's kicker is a Poisson train of pulses).

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth to tenth sets; the memory starts afresh at the run-in's first scan, 2 s before sample 0.
"""
