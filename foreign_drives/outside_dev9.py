"""Outside mechanisms, ninth DEVELOPMENT half (issue 31 part 4, set 9): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first eight sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev8`, :mod:`outside_sealed8`) have, with their laws in
the open. The ninth sealed half is :mod:`outside_sealed9`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, motor load moment, sensor, wheel torque); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed9` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 motor load moment, 14 wheel torque). About half of the fourteen are plain memoryless laws of new
kinds, half have a memory or a limit of their own (here: 1, 3, 5, 11 memoryless; 7, 9, 13 with a memory). Written
before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one
simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a CENTRIFUGAL SHOE CLUTCH: an auxiliary blower hangs on the motor's
   shaft behind a centrifugal clutch whose shoes engage smoothly around the speed Omega_e; once engaged the blower
   loads the motor with its square law: A*(Omega1/Omega_e)^2 * (1 + tanh((Omega1 - Omega_e)/w))/2 (a square law
   switched on smoothly by the speed itself: neither a power law alone nor a threshold's excess);
3. wheel torque x the wheel angle ONCE EVERY N TURNS: a Geneva (indexing) drive on the wheel shaft advances an index
   table once per N wheel turns; while its pin is in the slot (a window W of wheel angle from phi, every 2*pi*N of
   the wheel angle unwrapped from the run-in's start) it drags the wheel: -T*sign(Omega2) (a sub-harmonic of the
   wheel's rotation, a rectangular window: not locked to the stroke, not a harmonic of the turn);
5. clutch torque x the penetration through a SNAP-THROUGH (negative stiffness): the jaw faces carry Belleville
   (disc) springs of free height h; their force rises, flattens and falls again before the faces go solid:
   T_b*(p/h)*(1 - (p/h))*(1 - (p/(2h)))*4, added to the contact law while in contact (a non-monotone contact: a
   region of falling torque with rising penetration);
7. mass force x the mass speed through an ASYMMETRIC LAG: a pneumatic damper with a check valve drags the carriage:
   its chamber's pressure follows the carriage speed quickly while the speed rises (time constant tau_up) and bleeds
   off slowly through an orifice while it falls (tau_down); the force -c*m, m that lagged speed (a memory whose time
   constant depends on the direction of the change);
9. a2 sensor x a2's own past through a PLAY: a2's accelerometer has a loose seismic mass in its housing: its reading
   follows the acceleration only once the acceleration is more than h away from it, y -> a - h*sign(a - y) then,
   else held (a rate-independent hysteresis of the reading: a backlash operator inside the sensor);
11. mass force x the spring extension TIMES the sign of the mass speed: the spring's cable runs through a guide on the
    carriage and rubs it; the friction is proportional to the cable's tension k*z: -mu*k*z*tanh(v/v_s) (a Coulomb
    friction whose normal force is the spring's extension: not constant, not viscous);
13. a2 sensor x a2's own past through a FIXED-POINT SMOOTHING FILTER: a2's module smooths in integer arithmetic,
    y += q*round((a - y)/(q*2^k)) each sample (a first-order low-pass of time constant ~2^k samples whose output
    stalls while the error is below q*2^(k-1): a dead band inside a filter).
"""
