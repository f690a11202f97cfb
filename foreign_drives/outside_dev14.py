"""Outside mechanisms, fourteenth DEVELOPMENT half (issue 31 part 4, set 14): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first thirteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev13`, :mod:`outside_sealed13`) have, with their laws in
the open. The fourteenth sealed half is :mod:`outside_sealed14`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (motor
load moment, sensor, clutch torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed14` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 mass force). About half of the fourteen are plain memoryless laws of new kinds, half
have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory). Written before any
diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation
against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the WHEEL's angle: a disc brake on the motor's shaft whose caliper is pressed through a
   pushrod by a cam on the wheel's shaft (a mechanical timing linkage between the two shafts): T*max(0, sin(alpha2 +
   phi)) on the motor's load (a load on one shaft locked to the OTHER shaft's angle: the earlier motor loads locked to
   an angle read the motor's own angle or the stroke; the wheel's cam laws act on the wheel);
3. wheel torque x the wheel speed through a DEAD BAND: a hydraulic retarder on the wheel's shaft behind a bypass
   valve that stays open up to +-Omega_d: -c*sign(Omega2)*max(0, |Omega2| - Omega_d) (zero, then viscous beyond a speed:
   the thirteenth set's relief valve is viscous, then constant; the staged retarder steps; the earlier dead bands act
   on the mass speed, the jaw's angle or the contact torque);
5. clutch torque x the jaw's angle difference TIMES the motor speed squared: a leaf-spring coupling beside the jaw
   whose leaves are stiffened by their own centrifugal load: k*(Omega1/Omega_n)^2*(alpha1 - alpha2), Omega_n = 150
   rad/s (a stiffness scheduled by the speed: the earlier speed-dependent couplings beside the jaw are dampings of the
   slip, the leaf springs of the first set are stroke-gated);
7. mass force x the SPRING EXTENSION through a SATURATING RAMP: a hanging cable loop (festoon) that the spring's cable
   lifts off the floor as it extends: -w*(clip(z - z_c, -h, h) + h) (no force below z_c - h, its lifted weight growing
   linearly through 2h, then the whole loop's weight 2*h*w: the earlier laws of the extension are powers beyond a
   point, a periodic detent, products with the speed or sampled);
9. a2 sensor x the MASS SPEED: a2's sensing element has a velocity sensitivity (an electrodynamic element's back-emf
   term, zeroed at the line's speed v_0): y = x + K*(v - v_0) (the earlier sensor laws read the accelerations, the
   angles, the motor speed, the spring's extension or the pulse; none the carriage's speed);
11. motor load moment x the motor speed through a PEAK-HOLD: a drag-pointer governor on the motor's shaft: a ratchet
    holds the highest speed its flyweights reached, bleeding off with time constant tau, and a band brake loads the
    motor by c*max(0, m - Omega_s), m -> max(Omega1, m*exp(-dt/tau)) every 0.2 ms (m = Omega1 at the run-in's start)
    (a brake set by the speed's recent maximum: the ninth set's peak detector reads the wheel speed for the wheel);
13. clutch torque x the jaw's angle difference through a FRICTION SLIDER (a Jenkin element): a torsion spring beside
    the jaw anchored on a friction hub that slips once the spring's twist exceeds a: k*(D - q), q -> min(max(q, D - a),
    D + a) every 0.2 ms, D = alpha1 - alpha2 (q = D at the run-in's start) (an elastic, perfectly plastic element: its
    torque linear, then capped at +-k*a until the motion reverses; the sixth set's Dahl ring approaches its cap
    exponentially, the earlier play operators read the motor speed or the spring's extension).
"""
