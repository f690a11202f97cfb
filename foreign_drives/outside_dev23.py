"""Outside mechanisms, twenty-third DEVELOPMENT half (issue 31 part 4, set 23): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twenty-two sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev22`, :mod:`outside_sealed22`) have, with their laws in
the open. The twenty-third sealed half is :mod:`outside_sealed23`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (sensor,
sensor, clutch torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development half, the even
ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed23` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 mass force). Seven of the fourteen are plain memoryless laws of new kinds, seven have a memory
of their own (here: 1, 5, 9 memoryless; 3, 7, 11, 13 with a memory; the sealed half: three with a memory, four
memoryless). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each
strength is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.
Checked before the list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the
slip about +-5 rad/s, the jaw's angle difference within +-0.064 rad about a gap of +-0.051 rad, z 0.288-0.313 m, v
22.67-22.77 m/s, the electromagnetic torque 0.44-0.89 p.u. following the pulse, the pulse 60 ms every 0.25 s, a1 within
+-127 m/s^2, a2 within -1.7..+1.1 m/s^2): no row is a constant on this drive (each reads a quantity that moves with the
strokes, the jaw's contacts, the shafts' and the carriage's travel or the signal itself), and none is an earlier kind
moved to another balance or sensor: the pair (what it reads, how) is new against the registry of sets 1-22 (their kernel
slots and memory elements, and their sensor forms' docstrings).

Kinds (balance x what it reads, and how), the development half -- things a real drive has that nobody wrote down:

1. motor load moment x the CARRIAGE's SPEED through a CLIPPED LINEAR LAW: the drive's line-speed follower: a tacho
   wheel on the carriage feeds the motor's converter a torque trim proportional to the carriage's speed error over
   v_0, its authority limited to +-T by the converter's trim limit: T*clip((v - v_0)/dv, -1, 1), loading the motor
   while the carriage runs fast (the earlier laws of the carriage's speed alone are linear, an excess, a logarithm, a
   Lorentzian, a sigmoid, a tanh and whole steps, on the mass and the wheel -- none on the motor, none a clip; the
   motor's earlier term of the carriage is the rim's speed less the carriage's, linear);
3. wheel torque x the SPRING's EXTENSION through a RUN-TO-RUN CONTROLLER: an iterative-learning (stroke-to-stroke)
   tension trim: an auxiliary servo on the drum's shaft whose torque setpoint a PLC updates once per stroke, at each
   load pulse's start, from the mean extension over the stroke before: u_k = clip(u_{k-1} + g*(mean z - z_r), -U, U),
   -u on the wheel (u = 0 until the first update) (the earlier run-to-run controllers read the carriage's speed; the
   earlier memories of the extension are a delay, a Dahl element, a latch, a lag, a moving mean, an off-delay, an
   on-delay, a one-shot, a PI, a play, a PWM, a rate limiter, a squeal, a stroke peak, a stroke sample, a tank and a
   toggle -- none updated from a stroke's mean);
5. clutch torque x the JAW's ANGLE DIFFERENCE's MAGNITUDE TIMES the SLIP: a tapered-vane damper between the halves: the
   vane's clearance in its chamber narrows as the halves twist apart either way, so its damping grows with the twist:
   c*|D|*(Omega1 - Omega2) from the motor to the wheel, D the jaw's angle difference (the earlier dampings of the slip
   set by the jaw's angle are a Lorentzian (greatest at the gap's centre, the twenty-first set's metering land); the
   earlier laws of the jaw's angle are linear, a dead zone, face pulls, a Lorentzian, a power, a sigmoid, a sine and a
   tanh -- none its magnitude);
7. mass force x the SPRING's EXTENSION through a THREE-POINT STEP CONTROLLER: a hold-back magnet on the carriage whose
   excitation a raise/hold/lower controller of the tow cable's extension steps: one step up after z has stayed above
   z_r + b for t_s, one down after it has stayed below z_r - b for t_s (scanned every 0.2 ms), within [0, N_max] steps:
   -F*m, m the steps (m = 0 at the run-in's start) (the earlier step controllers read the motor's speed and the
   carriage's speed);
9. a1 sensor x the MOTOR's ELECTROMAGNETIC TORQUE, ADDITIVE: a1's MEMS readout picks up the stray field of the stator's
   current (its demodulator's reference coil sits in the motor's end winding's field), an offset proportional to the
   torque-producing current: y = x + k*t_e, t_e the electromagnetic torque [p.u.] (the earlier sensor terms of t_e are
   a hum whose amplitude it sets (the twenty-first set) and a pyroelectric rate of its square's heat; the earlier
   additive a1 terms of the drive are of the motor's angle and speed, of the jaw's torque, of the load pulse's
   rectangle (a solenoid's pickup, on or off) and of the time -- none following the motor's torque itself);
11. a2 sensor x the SIGNAL's SQUARE through a LAG, ADDITIVE (vibration rectification): a2's MEMS element rectifies
    vibration: an asymmetric squeeze film and a nonlinear spring shift its zero by a part of the recent mean square
    of the acceleration: y = x + k*m, m' = (x^2 - m)/tau (m = x^2 at the pre-roll's first sample) (the earlier
    even-order sensor errors are memoryless (a quadratic, a bilinear gain); the earlier memories of the signal's
    size set a gain (an automatic gain control) -- none an offset of its lagged power);
13. clutch torque x the SLIP through a PWM ACTUATOR: an eddy-current slip coupling beside the jaw whose field a PWM
    chopper switches fully on or off; its duty, taken at the start of each PWM period of n scans of 0.2 ms, follows the
    slip's excess over s_0: duty = clip((s - s_0)/s_w, 0, 1), m = 1 for the period's first round(duty*n) scans, else 0;
    c*m*(Omega1 - Omega2) from the motor to the wheel (the earlier PWM actuators read the wheel's speed and the
    extension; the earlier memories of the slip are a delay, a fill, a heat, an impact sample, a lag, a latch, a moving
    mean, a one-shot, an on-delay, a peak, a PI, a rate limiter, a squeal, a stroke sample, a tank and a thermostat --
    none a PWM).
"""
