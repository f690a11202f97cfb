"""Outside mechanisms, eighth DEVELOPMENT half (issue 31 part 4, set 8): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first seven sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev7`, :mod:`outside_sealed7`) have, with their laws in
the open. The eighth sealed half is :mod:`outside_sealed8`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed8` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 motor load moment, 14 mass
force). About half of the fourteen are plain memoryless laws of new kinds, half have a memory or a limit of their own
(here: 1, 5, 9 memoryless; 3, 7, 11, 13 with a memory). Written before any diagnose, analyze or proposal ran on them
(the commit history is the proof); each strength is set by one simulation against the clean drive of the same seed,
for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a RESONANCE PEAK: the cooling fan on the motor's shaft has a blade
   mode that its own blade passing excites near one shaft speed Omega_r; there the fluttering blades draw an extra
   load, A/(1 + ((Omega1 - Omega_r)/w)^2) (a load peaked in the speed, a Lorentzian of half-width w: neither a power
   law of the speed nor a threshold);
3. wheel torque x the wheel speed through a ONCE-PER-TURN PERIOD TACHOMETER: the PLC that brakes the wheel's overspeed
   measures the wheel speed as 2*pi over the time between the two latest passes of an index mark at the wheel angle
   phi (scanned every 0.2 ms, so updated once per wheel turn and held in between) and applies an eddy-current brake
   -K*max(0, W_m - Omega_0) (a measurement that is an event-timed reciprocal, not a sample of the speed);
5. clutch torque x the jaw's angle difference as a PERIODIC DETENT: a spring-loaded ball in the drive half rolls over
   a ring of dimples of angular pitch p in the driven half (the coupling's index detent): -T_d*sin(2*pi*D/p) at all
   times, in the gap and in contact (a torque periodic in the relative angle, several wells across the gap);
7. mass force x the mass speed through a RUN-TO-RUN controller: a linear booster on the carriage is set once per
   stroke: at each load pulse's first 0.2 ms scan the PLC takes the mean carriage speed over the scans since the last
   one, v_k, and changes the booster's force by -G*(v_k - v_ref), limited to +-F_max, held for the whole next stroke
   period (an integrator across strokes, updated from an average: a stroke-to-stroke adaptation);
9. a2 sensor x a2 through a WRAP-AROUND: a2's I/O module's fixed-point output overflows beyond +-R instead of
   clipping: a2 = ((a + R) mod 2R) - R (a two's-complement wrap: a large reading comes out with the opposite sign);
11. wheel torque x the wheel speed through a hidden SELF-EXCITED OSCILLATOR: the wheel's holding-brake pad drags
    lightly and squeals: a van der Pol oscillator x'' - w*g*(Omega2 - Omega_s)*(1 - x^2)*x' + w^2*x = 0 (its
    negative damping only above the speed Omega_s), the pad's force on the wheel -T*x/2 (x ~ 2 on the limit cycle;
    advanced every 0.2 ms; a floor keeps its amplitude at least 1e-3, the pad's contact noise): a tone of its own
    frequency that grows and dies with the wheel speed;
13. a2 sensor x a2's own past through an ADAPTIVE DELTA MODULATOR: a2 reaches the recorder through a CVSD codec (a
    telemetry link): each sample the decoded value moves one step s towards the input, s growing by a factor k after
    three equal steps in a row (to at most s_max) and falling by a factor d otherwise (to at least s_min) (slope
    overload and granular noise that adapt: not a fixed slew rate, not a quantiser).
"""
