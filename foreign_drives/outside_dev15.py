"""Outside mechanisms, fifteenth DEVELOPMENT half (issue 31 part 4, set 15): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first fourteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev14`, :mod:`outside_sealed14`) have, with their laws in
the open. The fifteenth sealed half is :mod:`outside_sealed15`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, sensor, mass force, motor load moment); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed15` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 motor load moment). About half of the fourteen are plain memoryless laws of new kinds,
half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory). Written before any
diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation
against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the SLIP's MAGNITUDE: an anti-clatter slip monitor (a tacho on each shaft) excites an
   eddy-current brake on the motor's shaft in proportion to how fast the jaw's halves move against each other, either
   way: c*|Omega1 - Omega2| on the motor's load (an even law of the slip on ONE shaft: the earlier laws of the slip
   are clutch torques, odd in it or half-wave, acting on both shafts; the earlier motor loads read Omega1, Omega2,
   r*Omega1 - v, the extension, the angles, the contact torque or the pulse);
3. wheel torque x the CARRIAGE's speed beyond a limit: a runaway guard on the carriage (a centrifugal governor on its
   guide roller) pulls, through a Bowden cable, a band brake on the wheel's shaft when the carriage overruns:
   -K*max(0, v - v_0) (a cross-domain law: the earlier wheel laws read the wheel's speed or angle, the extension, the
   pulse, the time or the jaw; the eleventh set's runaway governor brakes the motor from the wheel's speed);
5. clutch torque x the CUBE of the jaw's angle difference: an elastomer spider (a progressively hardening rubber
   element) bridging the jaw halves, in the gap and in contact: k3*(alpha1 - alpha2)^3 (a hardening spring across the
   backlash: the earlier springs across the jaw are linear -- the first sealed half's anti-backlash spring, the tenth
   set's stroke-switched leaf spring, the fourteenth's centrifugally stiffened one --, piecewise linear (the bumpers),
   periodic (the detent), non-monotone (the snap-through), an over-centre toggle or a Jenkin element);
7. mass force x the spring extension TIMES the load pulse: a gas spring hooked beside the spring between the carriage
   and the cable's clamp, pressurised by the press's valve during each stroke only: k_p*pulse*(z - z_0) along x (a
   stiffness on the carriage switched by the process: the tenth set's switched stiffness is across the jaw; the
   earlier stroke-related springs on the carriage are re-referenced at each stroke's start (the trapped air cushion)
   or stretched by the distance travelled since it (the hooked return spring), both acting between strokes too);
9. a2 sensor x the jaw's DRIVE-FACE CONTACT: a2's cable shield is grounded at both ends; the loop closes through the
   frame, the motor's shaft, the jaw's drive faces (their insulating coating worn through) and the wheel while the
   drive faces touch, and the loop's current shifts a2's zero: y = x + o*[drive faces in contact] (a sensor law of
   the clutch's contact state: the earlier sensor laws read the accelerations, the angles, the speeds, the spring's
   extension, the pulse or the time; none the jaw);
11. wheel torque x the spring extension through a PEAK-HOLD RESET AT EACH STROKE: a ratchet cable tensioner: a pawl on
    the cable guide follows the extension one way (it ratchets along while the extension grows and holds at its
    largest) and pulls a band brake on the wheel the tighter the further it has gone past z_0; the press's cam knocks
    the pawl out at each stroke's start and it picks up the extension there: -c*max(0, m - z_0), m -> z at each load
    pulse's first 0.2 ms scan, else m -> max(m, z) every 0.2 ms (m = z at the run-in's start) (a running maximum
    reset by the process: the drag pointers' peaks bleed off with a time constant and are never reset, the seventh and
    fourteenth sets' stroke-reset latches hold one bit, the stroke samples hold the value at the stroke's start);
13. mass force x the jaw's PENETRATION through a ONE-SHOT: a knock sensor on the coupling's housing: each time the
    jaw strikes (its penetration depth rising through p_t at a 0.2 ms scan) the PLC fires a rail brake on the carriage
    for T_h, not retriggered while it runs: -F while on (a timed brake triggered by the jaw's impacts: the earlier
    one-shots are triggered by the extension or the motor speed; the tenth sealed half's knock sensor samples the
    carriage's speed at each contact and holds a brake set from it until the next).
"""
