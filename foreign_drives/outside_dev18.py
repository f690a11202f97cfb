"""Outside mechanisms, eighteenth DEVELOPMENT half (issue 31 part 4, set 18): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first seventeen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev17`, :mod:`outside_sealed17`) have, with their laws in
the open. The eighteenth sealed half is :mod:`outside_sealed18`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (clutch
torque, motor load moment, mass force, wheel torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed18` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 motor load moment, 14 wheel torque). About half of the fourteen are plain
memoryless laws of new kinds, half have a memory or a limit of their own (here: 1, 5, 9, 13 memoryless; 3, 7, 11 with
a memory). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each
strength is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.
Checked before the list was committed: no row is a constant on this drive (each reads a quantity that moves with the
strokes, the jaw's crossings of the gap or the carriage's travel), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the CARRIAGE's POSITION through a WINDOW, times the motor speed: a dynamo on the motor's free
   shaft end feeds the carriage's heaters through a sectioned conductor rail; its collector shoe is on a live section
   for a length l of every section pitch L, and only then does the dynamo carry a load (a generator, proportional to
   its speed): c*Omega1 while (x - x_0) mod L < l, else 0, x the carriage's position unwrapped from the run-in's start
   (a motor load switched by the carriage's travel: the earlier motor windows are of the motor's own angle (the ninth
   sealed half's rotary distributor valve), of the pulse count (the nth-stroke pierce) and of the time; the fifth
   sealed half's rail joints are windows of the position on the carriage itself; the earlier motor loads of the
   carriage read its speed against the motor rim's (the first set's roller coupling));
3. wheel torque x the CARRIAGE's SPEED through a PEAK HELD SINCE EACH STROKE BEGAN: a stroke-by-stroke overspeed
   limiter: a drag pointer on the carriage's tacho, reset by the press's valve at each stroke's start, holds the
   highest carriage speed since, and a proportional brake on the wheel acts on its excess over v_r: -c*max(0, m - v_r),
   m -> v at each load pulse's first 0.2 ms scan, else max(m, v) (m = v at the run-in's start) (the fifteenth set's
   peak held since the stroke is of the extension, on the wheel's cable tensioner, the sixteenth set's on the motor;
   the fifteenth set's carriage-runaway brake on the wheel reads the carriage's speed without a memory; the earlier
   memories of the carriage's speed are a delay, a lag, an on-delay, a resonator, a run-to-run, an impact sample, a
   since-stroke integral, a slip hub, a rattle, a rate-state, all on the carriage);
5. clutch torque x the slip through an INDUCTION (KLOSS) CURVE: an eddy-current slip coupling beside the jaw (a drum
   on one shaft, an excited pole wheel on the other): its torque rises with the slip up to a pull-out torque T_k at the
   slip s_k and falls beyond: 2*T_k*(s/s_k)/(1 + (s/s_k)^2), s = Omega1 - Omega2, from the motor to the wheel, in the gap
   and in contact (a slip coupling whose torque peaks and falls again: the earlier slip couplings are linear from zero,
   one-way, hydrodynamic (the slip times the motor speed), a hysteresis coupling (tanh), of the second power, with a
   dead zone, gated, or with a memory; the eighth sealed half's eddy rail brake has the same characteristic of the
   carriage's own speed, braking the carriage against the ground, not coupling two shafts by their slip);
7. mass force x the CARRIAGE's SPEED through a LATCH RE-ARMED AT EACH STROKE: an overspeed catch on the carriage's rail
   wheel (a centrifugal pawl) drops a drag shoe onto the rail once the carriage's speed passes v_t and holds it down
   until the press's valve lifts it at the next stroke's start: -F*m, m -> 0 at each load pulse's first 0.2 ms scan,
   then m -> 1 at a scan with v > v_t (m = 1 at the run-in's start if v > v_t) (the seventh set's debounced overspeed
   brake is an on-delay of the carriage's speed, released as soon as the speed falls; the first sealed half's overspeed
   brake is memoryless; the earlier latches are of the wheel's speed and of the extension, both on the wheel);
9. a2 sensor x a2 TIMES a1 (a multiplicative crosstalk): a1's and a2's conditioners share one reference; a1's signal
   current loads it, so a2's gain follows a1's signal: y = x*(1 + g*a1), a1 the acceleration at a1's sensing element
   (a gain modulated by the other channel: the first sealed half's channel crosstalk adds a part of a1 to a2; the
   earlier gain modulations follow the load pulse (the supply sag), the time (the reference ripple), the motor's angle
   (the slip ring), the extension (the seventeenth set's strain gain), a2's own level (the bilinear gain, the
   auto-ranging, the AGC));
11. clutch torque x the jaw's ANGLE DIFFERENCE through a RATE LIMITER (a spring anchored on a creeping cylinder): a
    torsion bar bridging the jaw halves is anchored on the drive half through a small hydraulic rotary actuator whose
    pressure-compensated flow-control valve lets it creep at most R rad/s whatever the torque: -k*(D - m), m moving
    towards D by at most R*dt each 0.2 ms (m = D at the run-in's start), D the jaw's angle difference (a centring torque
    about an anchor that follows the angle at a limited speed: the fourteenth set's friction slider re-anchors when the
    torque passes its slip torque (a play), the seventeenth set's torsion bar at each stroke's start, the sixth sealed
    half's Dahl ring with the angle's changes, the tenth set's viscoelastic coupling is a lag of the slip; the sixth
    sealed half's rate limiter is of the extension, on the carriage, the twelfth sealed half's of the motor speed's
    follower, on the motor);
13. mass force x the CARRIAGE's POSITION through a RANDOM STEP PATTERN: the carriage's rail is laid in sections of
    length L, each with a small slope of its own; the carriage's weight along each section gives a force constant over
    the section and random from section to section: F*h(floor((x - x_0)/L)), h a fixed pseudo-random pattern in [-1, 1)
    (seed s), x the carriage's position unwrapped from the run-in's start (a random pattern of the carriage's travel:
    the tenth sealed half's worn chain is a random pattern of the wheel's angle, link by link, on the wheel, the
    eleventh set's upstream tension steps a random pattern of the time, on the wheel, the sixth sealed half's blank
    thickness of the stroke count, on the motor; the fifth sealed half's rail joints knock once per joint, all alike).
"""
