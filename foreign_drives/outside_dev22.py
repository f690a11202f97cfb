"""Outside mechanisms, twenty-second DEVELOPMENT half (issue 31 part 4, set 22): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twenty-one sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev21`, :mod:`outside_sealed21`) have, with their laws in
the open. The twenty-second sealed half is :mod:`outside_sealed22`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (sensor,
sensor, motor load moment, wheel torque); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed22` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 wheel torque). Seven of the fourteen are plain memoryless laws of new kinds, seven have a
memory of their own (here: 1, 9, 13 memoryless; 3, 5, 7, 11 with a memory; the sealed half: three with a memory, four
memoryless). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each
strength is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.
Checked before the list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the
slip about +-3 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s, the electromagnetic torque following the 1.6 p.u. pulse, the
pulse 60 ms every 0.25 s, the jaw's contacts and its free flights after each onset, the carriage travelling about 22.7
m a second): no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's
contacts, the shafts' and the carriage's travel or a random process), and none is an earlier kind moved to another
balance or sensor: the pair (what it reads, how) is new against the registry of sets 1-21 (their kernel slots and
memory elements, and their sensor forms' docstrings).

Kinds (balance x what it reads, and how), the development half -- things a real drive has that nobody wrote down:

1. motor load moment x the JAW's TRANSMITTED TORQUE through a SMOOTH STEP (a sigmoid): a load-sensing (Weston-type)
   brake on the motor's free shaft end: a ball ramp in the coupling's hub turns the torque the jaw transmits into an
   axial force that closes a friction brake, from about T_0 over a width w, its force limited by the ramp's stop:
   T*(1 + tanh((T_c - T_0)/w))/2, T_c the jaw's contact torque (0 in the gap) (the earlier laws of the contact torque
   are linear, its magnitude, its excess beyond a preload (a dead zone, a power) -- none a saturating step; the
   earlier smooth steps read the carriage's speed, the jaw's angle, the extension, the motor's speed, the contact mode
   and the slip);
3. wheel torque x the CARRIAGE's SPEED through an OFF-DELAY: a carriage overspeed switch (a trackside speed trap)
   applies the drum's brake while the carriage runs above v_t and an off-delay timer (scanned every 0.2 ms) keeps it
   applied for T_off after the speed last exceeded v_t: -T*m, m = 1 while v > v_t or within T_off of the last scan
   with v > v_t (the earlier off-delays read the wheel's speed (the eleventh set), the extension and the penetration;
   the earlier memories of the carriage's speed are a lag, a sampled delay, a run-to-run mean, an impact sample, a
   rate-and-state, an on-delay, a step controller, a slip hub, a rattle, a resonator, a stroke integral, a latch, a
   stroke peak and a moving mean -- none an off-delay);
5. clutch torque x the SLIP through a SAMPLE at each STROKE's START, TIMES the SLIP: an eddy-current slip coupling
   beside the jaw whose excitation a PLC sets once per stroke, at the load pulse's start, in proportion to the slip's
   magnitude it reads then: c*|s_k|*(Omega1 - Omega2) from the motor to the wheel, s_k the slip at the first 0.2 ms
   scan of the latest load pulse (at the run-in's first scan before the first), in the gap and in contact (the
   earlier stroke samples read the motor's speed, the extension and the jaw's angle; the earlier memories of the slip
   are a delay, a heat, an impact sample, a lag, a latch, a moving mean, a one-shot, an on-delay, a peak, a rate
   limiter, a squeal, a tank and a thermostat -- none sampled by the stroke);
7. mass force x the CARRIAGE's SPEED through a PI CONTROLLER with a SATURATED OUTPUT: a regenerative linear-motor
   speed limiter on the carriage under a digital PI loop (scanned every 0.2 ms) that only brakes: -u, u = K_p*e + I
   limited to [0, F_max], e = v - v_r, I += K_i*e*dt unless u is at a limit and e pushes it further (clamping
   anti-windup; I = 0 at the run-in's start) (the earlier PI controllers read the wheel's speed, the motor's speed and
   the extension; the twenty-first set's booster is a proportional loop on a boxcar mean of v);
9. a1 sensor x the MOTOR's SPEED SQUARED through a GAIN: a1's accelerometer turns with the motor's flywheel; the
   centripetal acceleration preloads its seismic mass across its suspension and changes its sensitivity with the
   square of the speed, calibrated at Omega_0: y = x*(1 - g*((Omega1/Omega_0)^2 - 1)) (the earlier sensor gains are
   modulated by the extension, by a1, by the time, by the process (the pulse, the contact) and by the signal itself
   -- none by a shaft's speed; the earlier sensor terms of the motor's speed are additive);
11. a2 sensor x the SIGNAL through a FIRST-ORDER SIGMA-DELTA MODULATOR: a2's converter is a first-order sigma-delta
    modulator clocked at the recorder's rate, full scale +-A, whose one-bit stream a boxcar of the last N bits
    decimates (a sinc filter without rate reduction): u[n] = u[n-1] + x[n]/A - b[n-1], b[n] = +1 if u[n] >= 0 else
    -1, y[n] = A*(the mean of b over the last N samples, over those there are at the pre-roll's start), u = 0 and no
    bit before the pre-roll's first sample (the earlier converters are quantisers, a non-uniform quantiser, an
    adaptive delta modulator (the eighth set), a block average and a sigma-delta module's overload reset (the sixth
    set, a dead time), none a noise-shaping one-bit loop);
13. motor load moment x the MOTOR's ANGLE through a TRAIN of DECAYS: a backstop (a ratchet freewheel) on the motor's
    shaft whose spring-loaded pawl clicks over its N teeth: each tooth's flank lifts the pawl and its drag decays as
    the pawl rides down it: T*exp(-((alpha1 - phi) mod (2*pi/N))/theta_d), theta_d the decay angle (the earlier laws
    of the motor's angle are sines, a half-wave sine, a rectangular window and a square wave; the earlier trains of
    decays are of the time (the tenth sealed half's shocks); the sawtooth of the wheel's angle rises linearly).
"""
