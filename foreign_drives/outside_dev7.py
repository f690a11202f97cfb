"""Outside mechanisms, seventh DEVELOPMENT half (issue 31 part 4, set 7): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first six sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev6`, :mod:`outside_sealed6`) have, with their laws in
the open. The seventh sealed half is :mod:`outside_sealed7`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed7` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 sensor, 14 mass force).
About half of the fourteen are plain memoryless laws of new kinds, half have a memory or a limit of their own (here:
1, 5, 9 memoryless; 3, 7, 11, 13 with a memory). Written before any diagnose, analyze or proposal ran on them (the
commit history is the proof); each strength is set by one simulation against the clean drive of the same seed, for
visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed TIMES the motor angle: an eddy-current brake disc (a retarder) on the motor's
   free shaft end runs with an axial wobble, so its air gap, and with it its drag coefficient, varies once per turn:
   T = -c*Omega1*(1 + e*sin(alpha1 + phi)) (a speed-proportional drag modulated by the angle: neither a viscous
   friction nor a ripple, their product);
3. wheel torque x the wheel speed through a LATCH reset by the stroke: a mechanical overspeed catch on the wheel
   shaft: when Omega2 rises above Omega_trip (scanned every 0.2 ms) a pawl drops and a friction brake -T holds the
   wheel until the next stroke's start, when the press's cam lifts the pawl again (set by a threshold, reset by an
   event);
5. clutch torque x the jaw's angle difference IN THE GAP, an inverse-square attraction: permanent magnets in the jaw
   faces (a magnetic latch against rattle) pull the halves towards whichever face is near: -T_m*((g0/(g_d + g0))^2 -
   (g0/(g_f + g0))^2), g_d = beta - D and g_f = beta + D the distances to the drive-side and far-side faces, 0 in
   contact (a negative stiffness in the gap; the contact law unchanged);
7. mass force x the mass speed through an ON-DELAY timer: the carriage's overspeed guard trips a rail brake only when
   v has stayed above v_max for T_d (a debounced switch, the PLC's TON timer, scanned every 0.2 ms), and releases it as
   soon as v falls below v_max: -F*on*tanh(v/0.01 m/s);
9. a2 sensor x a2 TIMES the load pulse: a2's sensor is ratiometric to a supply it shares with the press's valve;
   while the valve is energised (the pulse) the supply sags and the reading falls by g: a2 = a*(1 - g*pulse) (a gain
   switched by the process, not an offset);
11. motor load moment x the motor angle turned SINCE EACH STROKE'S START: a roll feed driven from the motor's shaft
    end through a clutch that the press's cam engages at each stroke's start and that lets go when the shaft has
    turned theta_f since (a fixed feed length): a load T while it feeds, so the feed's duration theta_f/Omega1
    follows the speed (an integrator reset by each stroke, an angle-metered window);
13. a2 sensor x a2's own recent samples: a2's I/O module has its spike suppression switched on: each output sample is
    the median of the last W input samples (a causal, nonlinear order-statistic filter with a memory of W samples:
    not a linear low-pass).
"""
