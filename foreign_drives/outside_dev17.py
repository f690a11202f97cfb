"""Outside mechanisms, seventeenth DEVELOPMENT half (issue 31 part 4, set 17): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first sixteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev16`, :mod:`outside_sealed16`) have, with their laws in
the open. The seventeenth sealed half is :mod:`outside_sealed17`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, mass force, clutch torque, motor load moment); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed17` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 mass force, 14 motor load moment). About half of the fourteen are plain
memoryless laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with
a memory). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each
strength is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.
Checked before the list was committed: no row is a constant on this drive (each reads a quantity that moves with the
strokes, the shafts' turns or the carriage's travel), and none is an earlier kind moved to another balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the SPRING EXTENSION through a STAIRCASE: a staged eddy-current brake on the motor's free shaft
   end whose coils a multi-contact tension switch on the spring's cable guide switches in one by one: T per whole step
   dz of the extension above z_0, T*floor((z - z_0)/dz) for z > z_0, else 0 (a quantised law of the extension: the
   earlier staircases read speeds (the fifth sealed half's encoder counts of the motor speed, the twelfth sealed
   half's retarder stages of the wheel speed); the earlier motor loads of the extension are a linear excess (the
   second set's overload band brake), the extension times the motor speed (the ninth sealed half) and a peak held
   since the stroke began (the sixteenth set's regenerative brake));
3. wheel torque x the UNWRAPPED wheel angle at a FRACTIONAL ORDER: a chain lubricator's crank pump geared down 1:N from
   the wheel's shaft: -A*sin(alpha2_u/N + phi), alpha2_u the wheel's angle unwrapped from the run-in's start (a smooth
   torque locked to the wheel at order 1/N, once every N turns: the catalogue's ripples and the cam follower have whole
   orders, the ninth set's Geneva drive acts in a window once every N turns, the tenth sealed half's worn chain is a
   random pattern link by link, the snail cam a sawtooth once per turn);
5. clutch torque x the slip SQUARED, SIGNED: a rotary hydraulic damper beside the jaw whose oil passes a sharp-edged
   orifice (turbulent flow: the pressure drop ~ flow^2): c*s*|s|, s = Omega1 - Omega2, from the motor to the wheel, in
   the gap and in contact (a slip coupling of the second power: the earlier slip couplings are linear from zero,
   one-way, hydrodynamic (the slip times the motor speed), a hysteresis coupling, gated, or with a memory; the
   catalogue's windage is a power of the wheel's own speed);
7. mass force x the MOTOR RIM's SPEED MINUS THE MASS SPEED through a DRY FRICTION: pinch rolls of the strip that the
   carriage carries are driven from the motor's shaft end through a slipping friction drive and drag the carriage
   towards the motor rim's speed: F*tanh((r*Omega1 - v)/w) (a saturating friction of a speed difference on the
   carriage: the first set's roller coupling is viscous and loads the motor, the thirteenth set's tracking conveyor is
   viscous and reads the wheel's speed; the earlier dry frictions on the carriage read its own speed);
9. a2 sensor x a2 TIMES the SPRING EXTENSION (a strain-sensitive gain): a2's piezoresistive element is bonded to the
   carriage's tow bracket, whose strain, with the cable's pull, changes the bridge's gauge factor: y = x*(1 + g*(z -
   z_c)) (a gain modulated by the load's extension: the second set's bracket tilt adds a term of z, the supply sag's
   gain follows the pulse, the reference ripple's the time, the slip ring's the motor angle);
11. wheel torque x the SLIP SAMPLED AT EACH JAW IMPACT: an anti-clatter actuator: a knock sensor on the coupling's
    housing triggers the PLC at each contact from the gap to sample the closing speed s = Omega1 - Omega2 and to set a
    hydraulic motor on the wheel's shaft that pushes the wheel towards the motor's speed until the next impact: +c*S,
    S the slip sampled at the scan after each contact began (S = the slip at the run-in's start) (a sample-and-hold of
    the slip timed by the drive's own impacts: the tenth sealed half's impact sample is of the carriage's speed, on the
    carriage; no earlier mechanism holds a value of the slip from one event to the next; the earlier wheel memories
    read the wheel's speed, its angle, the extension, the pulse or the jaw's contact);
13. clutch torque x the jaw's ANGLE DIFFERENCE through a STROKE SAMPLE (a spring re-anchored at each stroke): a torsion
    bar bridging the jaw halves is clamped to the drive half by a pneumatic clamp that the press's valve releases for
    an instant at each stroke's start: -k*(D - S), S = D at each load pulse's first 0.2 ms scan, held (S = D at the
    run-in's start), D the jaw's angle difference (a centring torque about a point that moves stroke by stroke: the
    first sealed half's anti-backlash spring is anchored at the gap's centre, the fourteenth set's friction slider
    re-anchors whenever the spring's torque exceeds its slip torque, the sixth sealed half's Dahl ring follows the
    angle's changes; the fifth sealed half's stroke sample is of the extension, on the wheel).
"""
