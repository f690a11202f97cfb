"""Outside mechanisms, seventeenth SEALED half (issue 31 part 4, set 17): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev17`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the spring extension through an OFF-DELAY: a tension switch on the spring's cable guide with a
   run-on timer: while the extension is above z_t, and for T_off after the last 0.2 ms scan at which it was, a
   holding brake on the motor's free shaft end pulls T: T*m, m -> 1 at a scan with z > z_t, -> 0 once T_off has passed
   since the last such scan (m = 1 at the run-in's start if z > z_t, else 0) (the eleventh set's off-delay is of the
   wheel speed, on the wheel, the fourteenth sealed half's of the jaw's penetration, on the clutch; the earlier motor
   loads of the extension are a linear excess, the extension times the motor speed and a peak held since the stroke
   began);
4. wheel torque x the slip through a PEAK DETECTOR with a decay: a slip-reading drag pointer: a tacho on each shaft
   feeds a peak detector (a diode into a capacitor bled by a resistor, time constant tau) whose output excites an
   eddy-current brake on the wheel: -c*max(0, m), m -> max(s, m*exp(-dt/tau)) every 0.2 ms, s = Omega1 - Omega2 (m = s
   at the run-in's start) (the earlier peak detectors hold the wheel speed on the wheel, the motor speed on the motor,
   the penetration on the clutch and the extension since each stroke; the fifteenth set's slip monitor is memoryless,
   on the motor);
6. clutch torque x the slip through a RATE LIMITER: a magnetorheological coupling beside the jaw whose coil current a
   controller sets from the slip, through a current source that slews at most R: c*m, m moves towards s = Omega1 -
   Omega2 by at most R*dt each 0.2 ms (m = s at the run-in's start) (a slew-limited copy of the slip: the earlier
   memories of the slip are a lag, a dead time, an on-delay, a heat, a pumped plate; the earlier rate limiters are of
   the extension, on the carriage, and of the motor speed's follower, on the motor);
8. mass force x the spring extension through a RELAY WITH HYSTERESIS: a two-point tension switch with a switching
   differential clamps a drag shoe on the carriage: -F*s, s switched to 1 when z rises above z_on and to 0 when it falls
   below z_off < z_on (scanned every 0.2 ms; s = 0 at the run-in's start) (the third set's relay is of the motor speed,
   on the motor; the earlier switches of the extension on the carriage are a one-shot timer and an impulse relay (a
   toggle), memoryless ones the festoon and the gas spring);
10. a2 sensor x the LOAD PULSE through a TRACK-AND-HOLD: a2's module has a blanking input: the PLC holds a2's
    track-and-hold while the press's valve is energised (to blank its switching noise), so a2 reads its value at the
    stroke's first sample throughout each stroke: y = x(t_p) while the pulse is on, t_p its start, else x (a hold gated
    by the press: the fourth set's telemetry hold is gated by the motor's angle, on a1; the supply sag's gain, the
    solenoid pickup and the stroke ringing follow the pulse without holding anything);
12. mass force x the carriage's POSITION through a SMOOTH SINE: the carriage's rail sags between its supports (a span
    L): the carriage's weight along the cambered rail gives F*sin(2*pi*x/L + phi), x its position unwrapped from the
    run-in's start (a smooth force of the travel, locked to neither shaft nor the time: the fifth sealed half's rail
    joints knock once per joint, the floor vibration is locked to the time, the eccentric roller to the wheel's angle);
14. motor load moment x the TIME through a SAWTOOTH: a pump on the motor's shaft end charges a lubrication accumulator
    that a timer dumps every T_f (its own period, locked to nothing of the press): the pump's load rises with the
    accumulator's pressure and drops at each dump: T*((t - t_0) mod T_f)/T_f (a ramp restarting at a fixed period:
    the first sealed half's clogging load rises once over the recording, the timed brush is a window of its own period
    on the wheel, the neighbour press's strikes are decays of its own period on the carriage, the catalogue's
    structural vibration is a sine).
"""
