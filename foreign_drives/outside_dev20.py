"""Outside mechanisms, twentieth DEVELOPMENT half (issue 31 part 4, set 20): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first nineteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev19`, :mod:`outside_sealed19`) have, with their laws in
the open. The twentieth sealed half is :mod:`outside_sealed20`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, mass force, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed20` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 mass force, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after. Checked before the
list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the slip about
+-3 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s, the pulse 60 ms every 0.25 s, the gap's half-width about 0.049 rad):
no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's crossings of the
gap, the wheel's turns, the carriage's travel or the mains' cycle), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the CARRIAGE's POSITION through a SAWTOOTH: a length marker: a pump on the motor's free shaft
   end works a marking cylinder on the carriage's strip whose return spring is wound in proportion to the carriage's
   travel since the last mark and released at each mark, one every L of travel: T*((x - x_0) mod L)/L, x the
   carriage's position unwrapped from the run-in's start (a motor load of the carriage's travel that rises and
   drops back: the earlier sawtooths are of the time (the seventeenth sealed half's timer-dumped pump), of the wheel's
   angle unwrapped (the eighth sealed half's snail cam) and of the stroke count (the sixth set's tray, on the
   carriage); the earlier laws of the carriage's position are a window times the motor's speed on the motor (the
   eighteenth set's dynamo), a window, a sine and a random pattern on the carriage, a half-wave sine on the wheel (the
   nineteenth set's rollers) and a2's tilt);
3. wheel torque x the SLIP through a SMOOTH STEP (a sigmoid): a gerotor pump whose two elements ride on the drive
   half and on the wheel's half pumps in proportion to the slip into a hydraulic motor on the wheel through a relief
   valve that opens once the drive half overruns the wheel by s_0: +T*(1 + tanh((s - s_0)/w))/2, s = Omega1 - Omega2
   (a wheel assist switched smoothly by the slip: the earlier laws of the slip on the wheel have a memory (the
   seventeenth set's impact sample, the nineteenth set's boxcar, the seventeenth sealed half's decaying peak); the
   earlier smooth steps are of the carriage's speed (the eleventh set), of the jaw's angle (the third set's Weston
   brake), of the extension (the sixteenth sealed half), of the motor's speed (the ninth set's blower, the twelfth
   sealed half's bypassed damper, which multiplies the slip) and of the contact mode (the eighteenth sealed half));
5. clutch torque x the jaw's ANGLE DIFFERENCE TIMES a HALF-WAVE RECTIFIED MAINS SINE, SQUARED: an electromagnetic
   centring latch across the jaw whose coil is fed from the 50 Hz mains through one diode: its pull, hence its
   centring stiffness, goes as the current's square, a half-wave rectified sine: -k*max(0, sin(2*pi*f*t + phi))^2*D,
   D the jaw's angle difference, in the gap and in contact, t the time (a centring stiffness across the jaw
   pulsating with a clock of its own: the earlier stiffnesses across the jaw are constant (the first sealed half),
   switched by the pulse (the tenth set), scheduled by the motor speed's square (the fourteenth set) or by the
   cable's extension (the nineteenth set), cubic (the fifteenth set), or re-anchored (the fourteenth, seventeenth and
   eighteenth sets); the earlier laws of the time at a fixed frequency are a sine on the carriage (the second set),
   a2's hum and a2's gain ripple (the second and seventh sealed halves));
7. mass force x the SPRING EXTENSION TIMES a SLOW COSINE of the WHEEL's UNWRAPPED ANGLE: the drum's level-wind lays
   the tow cable across the drum's width and back once every N turns, so the cable leaves the drum at a fleet angle
   that swings slowly with the turns; the pull along the track is the cable's pull times the cosine of that angle:
   -c*z*(1 - cos((theta - theta_0)/N)), theta the wheel's angle unwrapped from the run-in's start (the cable's pull
   modulated by the turns: the earlier laws of the wheel's unwrapped angle are on the wheel (the fifth set's rope
   layers, which multiply the extension into a wheel torque, the seventeenth set's lubricator crank, a sine, the
   third sealed half's spall, the eighth sealed half's snail cam, the tenth sealed half's chain links, the ninth set's
   Geneva drive); the earlier laws of the wheel's angle on the carriage are the second set's eccentric roller, a cosine,
   the seventh sealed half's stroke-gated sine and the nineteenth set's crossover window, none of the extension);
9. a1 sensor x the CLUTCH TORQUE TIMES the MOTOR SPEED's SQUARE: a1's sensing element sits on the web of the
   motor-side coupling flange, which twists with the torque it passes to the jaw; the twist tilts a1's tangential
   axis towards the radial, so that a1 reads that fraction of the centripetal acceleration: y = x + r*Omega1^2*e*T_c,
   e the web's twist per N*m, r = 0.15 m (a1's radius), T_c the jaw's torque (an additive a1 error of the jaw's
   torque: no earlier sensor term reads the jaw's torque; the first sealed half's cross-axis reading of the
   centripetal acceleration has a fixed tilt; the fifteenth set's ground loop reads the contact state, not its torque;
   the eighteenth sealed half's pyroelectric term reads the motor's torque through a heat lag);
11. wheel torque x the SPRING EXTENSION through a PI CONTROLLER with a SATURATED OUTPUT: a tension controller brakes
    the drum (a proportional valve on its disc brake) to hold the cable's extension at z_r: -u, u = K_p*e + I limited
    to [0, T_max], e = z - z_r, I += K_i*e*dt unless u is at a limit and e pushes it further (clamping anti-windup),
    scanned every 0.2 ms (I = 0 at the run-in's start) (the earlier PI controllers read the wheel's speed (the sixth
    sealed half, on the wheel) and the motor's speed (the fifteenth sealed half, on the motor); the earlier memories of
    the extension on the wheel are a latch, a stroke sample, a play, a peak held since the stroke began, a check
    valve's lag and an on-delay);
13. motor load moment x the SLIP through a RELAY FILLING a CYLINDER: a slip monitor's relay (a two-point switch with
    hysteresis: on above s_on, off below s_off, s = Omega1 - Omega2) opens a valve that fills a motor-side brake's
    cylinder over T_f and, released, drains it over T_e: T*m, m += dt/T_f while the relay is on, m -= dt/T_e while it
    is off, m in [0, 1], scanned every 0.2 ms (m = 0 at the run-in's start) (the earlier fills are of the pulse (the
    eleventh sealed half, across the jaw) and of the contact mode (the fifteenth sealed half, on the wheel); the
    earlier relays read the motor's speed (the third set), the jaw's angle (the eleventh sealed half) and the extension
    (the seventeenth sealed half), none behind a memory; the nineteenth sealed half's slip guard on the motor is a
    latch re-armed at each stroke, on or off at once).
"""
