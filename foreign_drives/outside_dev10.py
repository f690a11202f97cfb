"""Outside mechanisms, tenth DEVELOPMENT half (issue 31 part 4, set 10): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first nine sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev9`, :mod:`outside_sealed9`) have, with their laws in
the open. The tenth sealed half is :mod:`outside_sealed10`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (clutch
torque, sensor, wheel torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed10` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 mass force). About half of the fourteen are plain memoryless laws of new kinds, half have a
memory or a limit of their own (here: 1, 5, 9, 13 memoryless; 3, 7, 11 with a memory). Written before any diagnose,
analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation against the
clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the time since each stroke's start as a DAMPED RING: the press's crank train rings torsionally
   at each strike and the ringing torque reaches the motor's shaft: A*exp(-phi_p/tau)*sin(2*pi*f*phi_p) while the pulse
   is on, phi_p the time since the pulse began (a decaying oscillation locked to the stroke's start, in a balance: the
   catalogue's pulse is a rectangle, the third set's accumulator recharge decays from the falling edge without
   ringing, the third set's ringing is a2's reading of the frame, not a torque);
3. wheel torque x the wheel speed through a THERMAL CUT-OUT: an eddy-current brake on the wheel, -c*Omega2 while on,
   heats with its power c*Omega2^2 and cools with tau; a bimetal switch cuts it out when its heat passes H_off and
   back in below H_on < H_off (heat' = on*c*Omega2^2 - heat/tau, scanned every 0.2 ms): a relaxation oscillation of
   its own period, set by the heat's thresholds (a thermal integrator behind a hysteresis switch that it drives
   itself);
5. clutch torque x the jaw's angle difference TIMES the load pulse: during each stroke the press's valve also
   energises a magnet that presses an anti-rattle leaf spring across the jaw halves: pulse*k*D from the motor to the
   wheel, D the jaw's angle difference from the gap's centre, in the gap and in contact (a stiffness across the
   backlash switched by the process: neither always there nor a damping);
7. mass force x the spring extension through an IMPULSE (LATCHING) RELAY: a rail brake on the carriage switched by an
   impulse relay; a limit switch on the spring's bracket pulses its coil each time the extension rises past z_on
   (re-armed once it has fallen below z_off < z_on), and each pulse toggles the brake: -F while on (a binary divider
   of the drive's own events, scanned every 0.2 ms: a sub-harmonic made by the state, not by the stroke count);
9. a1 sensor x a1 through a mu-LAW COMPANDING codec: a1's rotating telemetry sends 8-bit mu-law codes (mu = 255, full
   scale A): c = round(127*sign(a)*ln(1 + mu*min(|a|, A)/A)/ln(1 + mu)), y = sign(c)*A*((1 + mu)^(|c|/127) - 1)/mu (a
   non-uniform quantiser: fine steps near zero, coarse ones near full scale);
11. clutch torque x the jaw's slip speed through a LAG: a viscous coupling beside the jaw filled with a viscoelastic
    (silicone) fluid: its torque c*m from the motor to the wheel at all times, m the slip Omega1 - Omega2 relaxed with
    the fluid's time tau (a first-order lag, advanced every 0.2 ms from m = the slip at the run-in's start; the first
    set's gap drag is the instantaneous viscous law);
13. wheel torque x the TIME SINCE THE JAW'S CONTACT BEGAN: a holding brake on the wheel interlocked with the coupling:
    a proximity switch across the jaw energises it while the jaw is in contact (either face), its field rising with
    the coil's L/R: -T*(1 - exp(-t_c/tau)), t_c the time since the contact began from the gap, 0 in the gap (a brake
    gated and timed by the jaw's own contact).
"""
