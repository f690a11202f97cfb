"""Outside mechanisms, twenty-first SEALED half (issue 31 part 4, set 21): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev21`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the WHEEL's SPEED through a RELAY, TIMES the MOTOR's SPEED: a wheel-overspeed relay (a two-point
   switch with hysteresis: on above Omega_on, off below Omega_off, Omega2 scanned every 0.2 ms) energises the field of
   an eddy-current brake on the motor's free shaft end, whose drag goes with the motor's speed: c*Omega1*r, r the
   relay's state (off at the run-in's start) (the earlier relays read the motor's speed (the third set), the jaw's
   angle (the eleventh sealed half), the extension (the seventeenth sealed half) and the slip (the twentieth set),
   none the wheel's speed; the earlier eddy brakes on the motor are excited by the extension, the jaw's gap, the
   carriage's position window and the motor's own speed);
4. wheel torque x the WHEEL's SPEED TIMES a FULL-WAVE MAINS SINE, SQUARED: an eddy-current brake on the drum fed from an
   unsmoothed full-wave rectifier: its field current is |sin| of the mains and its drag goes as the current's square
   times the drum's speed: -c*Omega2*sin(2*pi*f*t + phi)^2, t the time from sample 0 (the earlier wheel eddy brakes are
   constant, field-lagged behind the stroke, cut out thermally or pulse-width modulated; the earlier laws of the time
   at the mains' frequency are a2's hum, a2's gain ripple and the twentieth set's half-wave magnet across the jaw, none
   times a speed);
6. clutch torque x the SLIP through a PI CONTROLLER, TIMES the SLIP: an eddy-current slip coupling beside the jaw whose
   excitation a digital PI slip controller sets to hold the slip at s_r: c*u*(Omega1 - Omega2) from the motor to the
   wheel, u = K_p*e + I limited to [0, 1], e = s - s_r, I += K_i*e*dt unless u is at a limit and e pushes it further
   (clamping anti-windup), scanned every 0.2 ms (I = 0 at the run-in's start), in the gap and in contact (the earlier
   PI controllers read the wheel's speed (the sixth sealed half), the motor's speed (the fifteenth sealed half) and the
   extension (the twentieth set); the earlier slip-controlled couplings are a sampled delay (the twelfth sealed half)
   and a slew-limited current (the seventeenth sealed half));
8. mass force x the WHEEL's SPEED through a LORENTZIAN (a resonance): the tow cable's span between the drum and the
   carriage whirls when the drum's once-per-turn runout excites it near the span's natural frequency; the whirl's
   centrifugal pull adds to the cable's tension on the carriage, peaking at the resonant drum speed Omega_r:
   -F/(1 + ((Omega2 - Omega_r)/w)^2) (the earlier Lorentzians are of the motor's speed (the eighth set's fan flutter,
   on the motor), of the extension (the fourteenth sealed half's magnet) and of the stroke's time (the sixteenth set's
   shear); the earlier laws of the wheel's speed on the carriage are a blower's square (the ninth sealed half), a
   tracking conveyor and a timed rail brake);
10. a2 sensor x the SIGNAL through a PACKET LOSS CONCEALED BY REPETITION: a2 reaches the recorder over a wireless link
    in packets of L samples; a packet is lost at random at a rate p (u_j, the j-th of numpy default_rng(seed)'s uniform
    numbers, < p; packets counted from the pre-roll's first sample), and the receiver conceals a lost packet by
    repeating the last packet it received, sample for sample: y over packet j = y over packet j - 1 where lost, else x
    (the first packet is never lost) (the earlier random sensor errors are a1's telemetry bit errors and jitter (the
    eleventh and sixth sealed halves); the earlier holds repeat one value, never a block);
12. motor load moment x the MOTOR's SPEED through a KLOSS CURVE about a SYNCHRONOUS SPEED: an auxiliary asynchronous
    machine on the motor's free shaft end (a six-pole induction machine on the same grid, its synchronous speed Omega_s
    below the drive's speed) runs as a generator: its braking torque follows Kloss's law in its own slip u = Omega1 -
    Omega_s: 2*T_k*(u/u_k)/(1 + (u/u_k)^2), T_k its pull-out torque at the slip u_k (the earlier Kloss laws are of the
    slip across the jaw (the eighteenth set's induction coupling) and of the carriage's speed (the eighth sealed half's
    rail brake), both about zero; none of the motor's speed);
14. wheel torque x the WHEEL's SPEED through a SMOOTH STEP (a sigmoid): a centrifugal speed-limiting brake on the drum
    (as on hoists): its shoes fly out against their springs around Omega_e and rest on the drum at a force their stops
    limit: -T*(1 + tanh((Omega2 - Omega_e)/w))/2 (the earlier smooth steps are of the carriage's speed, the jaw's angle,
    the extension, the motor's speed, the contact mode and the slip; the earlier laws of the wheel's speed on the
    wheel are viscous, staged, a relief valve's clip, a bypass's dead zone and, behind memories, an overspeed latch,
    an off-delay, a peak, a tank, a PWM, a PI, a period tacho and a squeal).
"""
