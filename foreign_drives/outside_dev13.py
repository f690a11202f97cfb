"""Outside mechanisms, thirteenth DEVELOPMENT half (issue 31 part 4, set 13): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twelve sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev12`, :mod:`outside_sealed12`) have, with their laws in
the open. The thirteenth sealed half is :mod:`outside_sealed13`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (motor
load moment, sensor, clutch torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed13` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 mass force). About half of the fourteen are plain memoryless laws of new kinds, half
have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory). Written before any
diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation
against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a LOGARITHMIC (Eyring) law: a paste mixer (an agitator in a
   shear-thinning, yield-stress paste) on the motor's shaft end: c*ln(Omega1/Omega_0) above Omega_0, 0 below (a load
   that grows with the logarithm of the speed: the earlier motor loads are polynomial, power, constant-power, choked or
   resonant in the speed; the eleventh set's logarithm is a rate-and-state friction of the mass with a memory);
3. wheel torque x the wheel speed through a RELIEF VALVE: a gear pump on the wheel's shaft pumps through a throttle
   and a relief valve that cracks at Omega_r's pressure: -c*clip(Omega2, -Omega_r, Omega_r) (a viscous load that
   saturates at a speed: a kink from linear to constant; the earlier wheel laws of the speed are stairs, a PWM, a PI,
   thresholds with a memory, a tank or products);
5. clutch torque x the slip speed through a HYSTERESIS COUPLING: a permanent-magnet hysteresis coupling beside the
   jaw, whose torque is nearly independent of the slip speed once it slips: T_h*tanh((Omega1 - Omega2)/w), in the gap
   and in contact (a Coulomb-like law of the slip, not of the faces' pressure: the second set's dry friction acts in
   contact only and scales with the contact's force; the earlier couplings beside the jaw are viscous);
7. mass force x the WHEEL speed MINUS the mass speed: a powered roller conveyor under the carriage whose speed follows
   a tacho on the wheel's shaft (an electronic line shaft, no mechanical reaction on the wheel), its rollers dragging the
   carriage towards the belt speed: c*(r_b*Omega2 - v) (a viscous coupling of the mass to the other shaft's speed:
   the first set's roller coupling runs from the motor and loads both; the ninth set's sail reads Omega2 squared);
9. a2 sensor x the motor ANGLE TIMES the motor speed: the motor rotor's magnets induce a voltage in a2's unshielded
   cable that runs past the motor: y = x + A*(Omega1/Omega_n)*sin(p*alpha1 + phi), Omega_n = 150 rad/s (Faraday: an
   interference locked to the motor's angle whose amplitude grows with its speed; the first set's rotating gravity and
   the third set's slip ring are on a1, the second set's hum is locked to the time);
11. motor load moment x the motor speed through a ONE-SHOT: an overspeed switch on the motor's shaft fires a timed
    brake: when Omega1 rises through Omega_t (from at or below it) and the brake is off, -T for a fixed time T_h, then
    off until the next rising crossing (the one-shot reads the motor speed every 0.2 ms, off at the run-in's start; the
    fourth set's one-shot reads the spring's extension for the mass, the ninth set's the wheel angle);
13. clutch torque x the slip speed through a SLIP-PUMPED PLATE CLUTCH (a Haldex-type coupling): a reversible gerotor
    between the two halves pumps oil into a plate clutch's piston chamber when the motor overruns the wheel and out
    again when the wheel overruns, the chamber leaking through an orifice: m -> max(0, m + dt*(a*(Omega1 - Omega2) -
    b*sqrt(m))) every 0.2 ms (m = 0 at the run-in's start), the plates passing c*m*tanh((Omega1 - Omega2)/w) (a
    friction whose clamping pressure the slip's own history builds; the eleventh set's fill ramps with the pulse).

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth to twelfth sets; the memory starts afresh at the run-in's first scan, 2 s before sample 0.
"""
