"""Outside mechanisms, twelfth DEVELOPMENT half (issue 31 part 4, set 12): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first eleven sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev11`, :mod:`outside_sealed11`) have, with their laws in
the open. The twelfth sealed half is :mod:`outside_sealed12`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, sensor, wheel torque, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed12` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 clutch torque). About half of the fourteen are plain memoryless laws of new kinds, half have a
memory or a limit of their own (here: 1, 5, 7, 13 memoryless; 3, 9, 11 with a memory). Written before any diagnose,
analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation against the
clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a CHOKED quadratic law: a hydraulic (water-brake) dynamometer on the
   motor's shaft end, whose inlet chokes above Omega_c: c*Omega1*clip(Omega1, +-Omega_c) (quadratic in the speed below
   Omega_c, linear above it: a law that changes its order at a speed; no earlier motor term is a power law whose
   exponent falls with the speed);
3. wheel torque x the wheel speed through an ORIFICE-DRAINED TANK: a hydraulic retarder on the wheel filled by a small
   gear pump on the wheel's shaft: its working chamber's fill m rises with a*Omega2 and drains through an orifice,
   m' = a*Omega2 - b*sqrt(m) (m >= 0, every 0.2 ms, m = 0 at the run-in's start), the wheel braked with -k*m (the eighth
   set's tank is filled by the stroke's pulse and loads the mass; here the shaft fills its own retarder);
5. clutch torque x the slip speed TIMES the motor speed: a hydrodynamic (Foettinger) coupling beside the jaw, whose
   torque grows with the slip and with the pump wheel's speed: c*(Omega1 - Omega2)*Omega1/Omega_n, Omega_n = 150 rad/s
   (a product of two states: the first set's gap drag and the eleventh set's couplings are linear in the slip alone);
7. mass force x the mass speed TIMES the motor speed: an eddy-current rail brake on the carriage whose field coils are
   fed by a tacho-generator on the motor's shaft: -c*(Omega1/Omega_n)*v, Omega_n = 150 rad/s (a damping of the mass set
   by the other side's speed; the earlier eddy brakes have a fixed field);
9. a2 sensor x a2's own past through a CABLE ECHO: a2's long, badly terminated signal cable reflects its signal back
   once: y[n] = x[n] + r*x[n - d] (a comb filter: one delayed copy of the signal, d samples at 50 kHz; none of the
   earlier sensor faults adds a delayed copy);
11. mass force x the spring's extension through a LOST-MOTION LINK: the spring's cable carries a dog that runs in a
    slot of +-a in a slider which a friction clamp holds on the carriage; across the slot the dog's rubber pads push
    F*(z - s)/a, at the slot's end it drags the slider along with +-F: s follows z as a play operator of half-width a
    (s -> min(max(s, z - a), z + a) every 0.2 ms, s = z at the run-in's start), the carriage pulled along x with
    +F*(z - s)/a (a friction element behind a play, in parallel with the spring; the fifth set's play works on the
    motor speed, the sixth set's Dahl ring is a smooth friction law of the jaw's angle);
13. wheel torque x the wheel speed TIMES the load pulse: a die-cushion pump driven by the wheel's shaft, switched to
    pressure only while the stroke's pulse is on: -c*Omega2*P (a viscous load gated by the stroke; the first set's
    process brake is a constant torque during the pulse).

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth to eleventh sets; the memory starts afresh at the run-in's first scan, 2 s before sample 0.
"""
