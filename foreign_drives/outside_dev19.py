"""Outside mechanisms, nineteenth DEVELOPMENT half (issue 31 part 4, set 19): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first eighteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev18`, :mod:`outside_sealed18`) have, with their laws in
the open. The nineteenth sealed half is :mod:`outside_sealed19`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, mass force, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed19` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 mass force, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after. Checked before the
list was committed: no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's
crossings of the gap, the wheel's turns or the carriage's travel), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the TIME SINCE THE LATEST STROKE BEGAN through a RAMP held at its top: a pump on the motor's
   free shaft end charges the press's hydraulic accumulator, which the press empties at each stroke's start; a
   constant-flow pump into a spring accumulator sees a pressure rising linearly with the time since, until the relief
   valve opens at full charge: T*min(1, (t - t_s)/T_c), t_s the latest load pulse's start, on or off (a motor load
   that ramps up after each stroke and holds: the earlier motor loads timed by the stroke are a decay after the
   pulse's falling edge (the third set), a decaying oscillation (the tenth set) and a peak at a set delay (the
   sixteenth set); the first set's process brake on the wheel rises with its actuator's lag only while the pulse is
   on; the seventeenth sealed half's ramp restarts at a period of its own, locked to no stroke; the first set's
   creeping resistance ramps once over the recording, on the carriage);
3. wheel torque x the CARRIAGE's POSITION through a HALF-WAVE RECTIFIED SINE: the tow cable runs from the drum along
   the track over spring-loaded guide rollers at a pitch L; where the cable's clamp rides over a roller it presses it
   down and drags on the cable, hence on the drum: -T*max(0, sin(2*pi*(x - x_0)/L))^2, x the carriage's position
   unwrapped from the run-in's start (a wheel torque of the carriage's travel: the earlier laws of the carriage's
   position act on the carriage (the fifth sealed half's rail joints, a window times its speed; the seventeenth sealed
   half's smooth force, a sine; the eighteenth set's rail sections, a random pattern) or on the motor (the eighteenth
   set's rail-section dynamo, a window times the motor speed); the earlier half-wave sines are of the motor's angle
   (the first set's crank pump), of the wheel's angle (the second sealed half's tooth, the fourteenth set's timing
   linkage) and of the unwrapped wheel angle (the third sealed half's non-integer order));
5. clutch torque x the jaw's ANGLE DIFFERENCE TIMES the SPRING EXTENSION: a pneumatic torsion bellows (an air spring)
   bridges the jaw halves; it is fed from the cable's tension cylinder, so its pressure, hence its centring stiffness,
   follows the cable's extension: -k*(z - z_0)*D, D the jaw's angle difference, in the gap and in contact (a centring
   stiffness across the jaw scheduled by the load's cable: the earlier stiffnesses across the jaw are constant (the
   first sealed half), switched by the pulse (the tenth set), scheduled by the motor speed's square (the fourteenth
   set), cubic (the fifteenth set), or re-anchored (the fourteenth, seventeenth and eighteenth sets); the sixteenth
   set's friction plate pressed by the cable is a dry friction of the slip, not a stiffness of the angle);
7. mass force x the WHEEL's ANGLE through a ONCE-PER-TURN WINDOW: the drum's rope grooving has a crossover (a
   counter-grooved drum): once per turn, over an arc w of the wheel's angle, the rope climbs the crossover and jerks
   the tow cable back: -F while (alpha2 - alpha_0) mod 2*pi < w, else 0 (a rectangular window of the wheel's angle on
   the carriage: the earlier forces of the wheel's angle on the carriage are smooth (the second set's unbalance, a
   cosine; the seventh sealed half's stroke-gated sine); the earlier windows of the wheel's angle are on the wheel
   (the ninth set's Geneva drive, once every N turns); the ninth sealed half's square wave is of the motor's angle, on
   the motor);
9. a2 sensor x the CARRIAGE's POSITION through a COSINE (a tilt into gravity): the carriage's rail undulates with a
   wavelength L (a wavy track); the carriage pitches with the rail's slope, tilting a2's axis into gravity: y = x +
   A*cos(2*pi*(x_c - x_0)/L), x_c the carriage's position unwrapped from the run-in's start (an additive error locked
   to the carriage's travel: the earlier additive sensor errors are of the motor's angle (the first set's rotating
   gravity, the thirteenth set's interference), of the time, of the carriage's or the motor's speed (the fourteenth
   set, the fifteenth sealed half), of the contact state (the fifteenth set); the eighteenth set's rail slopes are a
   force on the carriage, not a reading);
11. wheel torque x the SLIP through a MOVING AVERAGE (a boxcar): an anti-clatter controller averages a slip monitor's
    reading over the last n 0.2 ms scans and drives a hydraulic torque motor on the wheel towards the motor's speed:
    +c*m, m the mean of s = Omega1 - Omega2 over the last n scans (all n = s at the run-in's start) (the earlier
    memories of the slip are a lag, a fill, a delay, a tank, an on-delay, an off-delay, a heat integrator, an impact
    sample, a decaying peak and a rate limiter, none an average over a window; the tenth sealed half's
    boxcar is of the motor's speed, on the motor; the seventeenth set's anti-clatter actuator on the wheel samples the
    slip at the jaw's impacts);
13. motor load moment x the jaw's CONTACT POWER through a DECAYING PEAK: an impact-severity meter on the coupling's
    guard (a peak hold with a bleed of the power the jaw's contact dissipates) sets the motor's eddy-current brake, so
    that the drive half closes on the jaw more softly after hard impacts: c*m, m -> max(P, m*exp(-dt/tau)) every 0.2
    ms, P = |T_c*D'| the contact law's power (0 in the gap; m = P at the run-in's start) (the fifth set's impact
    softening is a lag of the contact's power, on the clutch; the earlier decaying peaks are of the wheel's speed (the
    ninth sealed half), the penetration (the seventh sealed half), the motor's speed (the fourteenth set) and the slip
    (the seventeenth sealed half); no earlier motor load reads the contact's power).
"""
