"""Outside mechanisms, twenty-fourth SEALED half (issue 31 part 4, set 24): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev24`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the SLIP through an OFF-DELAY: a slip monitor on the coupling switches the drive's braking
   resistor onto the motor whenever the motor's half runs ahead of the wheel by more than s_t, and its relay holds it
   in for t_h after the slip last exceeded s_t: T*m, m = 1 from a scan with Omega1 - Omega2 > s_t until t_h after the
   last such scan, else 0 (the earlier off-delays read the wheel's speed, the carriage's speed, the penetration depth
   and the extension; the earlier memories of the slip are a delay, a fill, a heat, an impact sample, a lag, a latch,
   a moving mean, a one-shot, an on-delay, a peak, a PI, a PWM, a rate limiter, a squeal, a stroke sample, a tank and
   a thermostat -- none an off-delay);
4. wheel torque x the SPRING's EXTENSION TIMES a SINE of the WHEEL's ANGLE: the drum is out of round (its barrel
   eccentric by e to its shaft): the tow cable's lever arm on the drum varies once a drum turn, and with it the torque
   the cable's pull puts on the drum: -K*z*sin(alpha2 + phi), K = the spring's pull per m of extension times e (the
   earlier laws of the wheel's angle on the wheel are sines, rectified sines, a Geneva gate, a count's residue, hashed
   steps and the unwrapped angle times the extension (the rope's layers) -- none the extension times a sine of it);
6. clutch torque x the SLIP through a SATURATING RISE from an ENGAGEMENT SLIP: a one-way (sprag) clutch beside the jaw
   whose sprags engage once the motor's half overruns the wheel by s_0 and drive through a wet friction band; the
   band's oil film builds its torque up as 1 - exp(-(s - s_0)/w): T*(1 - exp(-(s - s_0)/w)) for s = Omega1 - Omega2 >=
   s_0, else 0, from the motor to the wheel (the earlier one-way law of the slip is a linear excess (an overrunning
   viscous coupling); the earlier saturating laws of the slip are two-way (tanh) -- none a one-way saturating rise);
8. mass force x the WHEEL's SPEED through a STROKE PEAK: a peak-reading drum tachometer, reset by the press's valve at
   each load pulse's start, drives a hold-back magnet on the carriage from its excess over Omega_t: -c*max(0, m -
   Omega_t), m the highest drum speed since the stroke's start (the earlier stroke peaks read the extension and the
   carriage's speed; the earlier memories of the wheel's speed are a delay, a latch, a lag, a moving mean, an
   off-delay, a one-shot, a peak (decaying), a PI, a PWM, a rattle, a squeal, a tank, a thermostat and a toggle --
   none a peak since the stroke's start);
10. a2 sensor x the SIGNAL's ENVELOPE through a NOISE GATE (a squelch): a2's wireless transmitter sleeps to save its
    battery: it sends zeros while a peak detector of |x| (instant attack, decay tau) stays below T and wakes at the
    first sample it rises above: y = x while e > T, else 0, e[n] = max(|x[n]|, e[n-1]*exp(-1/(fs*tau))) (the earlier
    sensor errors of the signal's size that depend on its past are an AGC, an auto-ranging, an overload recovery (zero
    while too BIG), a transmitter dead band (holds), a loose mass, a baseline restorer and a hysteresis -- none a gate
    closing while it is small);
12. a2 sensor x the MOTOR's ELECTROMAGNETIC TORQUE, MULTIPLICATIVE: a2's conditioner is fed from the drive's auxiliary
    winding, whose voltage sags with the motor's current; the ratiometric bridge's gain sags with it: y =
    x*(1 - g*(t_e - t_0)), t_e the electromagnetic torque [p.u.] (the earlier sensor terms of t_e are a1's additive
    stator-field pickup, a1's torque-following hum and a1's pyroelectric heat; the earlier supply-sag gain of a2
    follows the load pulse's rectangle -- none a gain following the motor's torque);
14. clutch torque x the SLIP TIMES a HALF-WAVE of the MAINS: an eddy-current slip coupling beside the jaw whose field
    coil is fed by an unsmoothed half-wave rectifier: its field follows each positive half cycle and its torque the
    field's square: c*max(0, sin(2*pi*f*t + phi))^2*(Omega1 - Omega2) from the motor to the wheel (the earlier
    mains-fed terms are the wheel's AC-fed eddy brake (of the wheel's speed) and the jaw's half-wave centring magnet
    (of the jaw's angle); the earlier products of the slip are with the motor's speed, the jaw's angle, the
    extension, the pulse and memories -- none with the mains).
"""
