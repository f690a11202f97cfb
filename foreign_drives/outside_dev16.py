"""Outside mechanisms, sixteenth DEVELOPMENT half (issue 31 part 4, set 16): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first fifteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev15`, :mod:`outside_sealed15`) have, with their laws in
the open. The sixteenth sealed half is :mod:`outside_sealed16`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, wheel torque, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed16` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 wheel torque, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the LOAD PULSE's AGE through a RESONANCE-SHAPED PEAK: a flying shear on the motor's free shaft
   end cuts the strip once per stroke, at t_c into it; its cutting load rises and falls about that instant:
   A/(1 + ((tau - t_c)/w)^2) on the motor's load while the pulse is on, tau the time since the pulse began (a load
   peak inside each stroke at a set delay: the earlier motor loads of the pulse are the accumulator's recharge, the
   n-th stroke's pierce, the stroke's torsional ringing, the metered roll feed (with the motor angle), the strain-rate
   forming load (the pulse times the speed) and the batch's random strokes; the eighth set's Lorentzian is a
   resonance of the mass speed on the carriage);
3. wheel torque x the MOTOR SPEED SQUARED: a hydrostatic booster: a gear pump on the motor's shaft end feeds a
   hydraulic motor on the wheel's shaft through a fixed orifice; the orifice's pressure drop, ~ flow^2 ~ Omega1^2,
   drives the wheel: +c*Omega1*|Omega1| on the wheel (a wheel law of the MOTOR's speed: the earlier wheel laws read the
   wheel's speed or angle, the extension, the pulse, the time, the jaw, the contact torque or the carriage's speed;
   the motor-side laws of the wheel's speed are the runaway governor and the hydraulic lag brake, on the motor);
5. clutch torque x the SLIP's direction TIMES the SPRING EXTENSION beyond a reference: a friction plate beside the
   jaw pressed through a lever by the spring's cable (the further it is stretched, the harder the plate is pressed):
   mu_k*max(0, z - z_0)*tanh((Omega1 - Omega2)/w) (a dry friction across the jaw whose normal force is the load's
   cable: the earlier slip couplings are viscous, overrunning, hydrodynamic, hysteresis, plate (pumped by the slip),
   thermally thinned or gated by the motor speed or the pulse (the stroke leaf spring); no clutch law reads the
   spring's extension);
7. mass force x the MOTOR ANGLE TIMES THE MOTOR SPEED SQUARED: the motor's rotor unbalance (e*m_r) shakes the common
   base frame, and the carriage on its rail feels the frame's motion: A*Omega1^2*sin(alpha1 + phi) along x (a force on
   the carriage locked to the MOTOR's angle: the eccentric roller is locked to the wheel's angle, the hold-down roller
   (sealed 7) to the pulse times the wheel's angle, the rail's waviness to the carriage's position; the first set's
   rotating gravity is a1's, of the motor angle alone);
9. a2 sensor x the CARRIAGE SPEED's DIRECTION: a2's cable rolls in the carriage's drag chain; the cable's
   triboelectric charge flips with the chain's direction of travel and shifts a2's zero: y = x + o*tanh(v/v_s) (a
   saturating, odd zero shift of the speed: the fourteenth set's velocity sensitivity is linear in v, the ground loop
   switches with the jaw's contact, the tacho's drop follows the motor speed);
11. mass force x the WHEEL SPEED through a ONE-SHOT: an overspeed switch on the wheel's shaft fires the carriage's rail
    brake for T_h each time the wheel's speed rises through Omega_t (scanned every 0.2 ms; not retriggered while it
    runs): -F while on (a timed brake on the carriage fired by the wheel: the earlier one-shots are fired by the
    extension (the impulse relay brake is a toggle), the motor speed (the overspeed timed brake, on the motor), the
    wheel's angle (the cam switch, on the wheel) or the jaw's impacts (the knock-triggered rail brake); the seventh
    set's debounced overspeed brake on the carriage reads the carriage's own speed);
13. motor load moment x the spring extension through a PEAK-HOLD RESET AT EACH STROKE: a peak-reading load cell on the
    spring's cable sets a regenerative brake on the motor from the largest extension since the stroke began (the PLC
    clears the peak at each stroke's start): c*max(0, m - z_0), m -> z at each load pulse's first 0.2 ms scan, else
    m -> max(m, z) every 0.2 ms (m = z at the run-in's start) (the fifteenth set's ratchet is this memory on the
    WHEEL; the earlier motor loads of the extension are memoryless (the overload band brake, the magnetic-particle
    brake times the speed)).
"""
