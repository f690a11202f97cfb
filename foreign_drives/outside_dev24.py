"""Outside mechanisms, twenty-fourth DEVELOPMENT half (issue 31 part 4, set 24): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twenty-three sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev23`, :mod:`outside_sealed23`) have, with their laws in
the open. The twenty-fourth sealed half is :mod:`outside_sealed24`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, sensor, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed24` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 clutch torque). Seven of the fourteen are plain memoryless laws of new kinds, seven
have a memory of their own (here: 5, 7, 9 memoryless; 1, 3, 11, 13 with a memory; the sealed half: three with a
memory, four memoryless). Written before any diagnose, analyze or proposal ran on them (the commit history is the
proof); each strength is set by one simulation against the clean drive of the same seed, for visibility, and not
changed after. Checked before the list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2
148.2-153.9 rad/s, the slip about +-5 rad/s, the jaw's angle difference within +-0.064 rad about a gap of +-0.051 rad,
so a penetration of up to about 0.013 rad, z 0.288-0.313 m, v 22.67-22.77 m/s, the carriage's position from 0 at the
run-in's start to about 136 m at a 4 s recording's end, the electromagnetic torque 0.44-0.89 p.u. following the pulse,
the pulse 60 ms every 0.25 s, a1 within +-127 m/s^2, a2 within -1.7..+1.1 m/s^2): no row is a constant on this drive
(each reads a quantity that moves with the strokes, the jaw's contacts, the shafts' and the carriage's travel or the
signal itself), and none is an earlier kind moved to another balance or sensor: the pair (what it reads, how) is new
against the registry of sets 1-23 (their kernel slots and memory elements, and their sensor forms' docstrings).

Kinds (balance x what it reads, and how), the development half -- things a real drive has that nobody wrote down:

1. motor load moment x the JAW's PENETRATION DEPTH through an ON-DELAY: a jam guard: a proximity switch at the jaw sees
   it bottomed deeper than p_t (the insert squeezed hard); once the depth has stayed beyond p_t for t_d (scanned every
   0.2 ms) the guard's relay sets a shoe brake on the motor's shaft, released at the first scan the depth is back
   within p_t: T*m, m = 1 while set, else 0 (the earlier on-delays read the gap distance, the slip, the carriage's speed
   and the extension; the earlier memories of the penetration depth are a lag, a latch, an off-delay, a one-shot, a
   peak and a tank -- none an on-delay);
3. wheel torque x the SPRING's EXTENSION through a SINCE-STROKE INTEGRAL: a stroke-dumped hydraulic drum brake: oil is
   metered into the brake's cylinder through a valve that the tow's dancer opens in proportion to the cable's
   extension, and the press's valve dumps the cylinder at each load pulse's start: -c*m, m the integral of z since the
   stroke's start (the earlier since-stroke integrals read the motor's speed and the carriage's speed; the earlier
   memories of the extension are a Dahl element, a delay, a latch, a lag, a moving mean, an off-delay, an on-delay, a
   one-shot, a PI, a play, a PWM, a rate limiter, a run-to-run controller, a squeal, a step controller, a stroke peak,
   a stroke sample, a tank and a toggle -- none an integral);
5. clutch torque x the JAW's ANGLE DIFFERENCE TIMES a SINE of the MOTOR's ANGLE: a thin laminated-disc anti-rattle
   spring across the jaw with one of its bolts loose: the pack's torsional stiffness varies once a motor turn as the
   loose bolt's side passes under load: k*(1 + e*sin(alpha1 + phi))*D from the motor to the wheel, D the jaw's angle
   difference (the earlier stiffnesses across the jaw are constant, hardening, set by the motor's speed, by the
   stroke, by a half-wave supply in time and by the tow's extension -- none by the shaft's own angle);
7. mass force x the CARRIAGE's POSITION through a LINEAR EXCESS: the carriage's trailing power cable is paid out from a
   spring-driven cable reel at the track's start; the reel's spring winds up as the cable pays out, so its pull back on
   the carriage grows with the carriage's travel beyond x_0: -k*max(0, x_c - x_0), x_c the carriage's position from
   the run-in's start (the earlier laws of the carriage's position are periodic: a gate, a sine, a rectified sine, a
   count's residue, hashed steps -- none growing with the travel);
9. a1 sensor x the SIGNAL through a CUBIC EXPANSION: a1's capacitive MEMS element has an electrostatic spring: the
   readout's bias voltage pulls the proof mass towards whichever electrode it nears, softening the suspension more the
   further it is deflected, so the reading grows faster than the acceleration: y = x*(1 + (x/a_e)^2) (the earlier
   memoryless sensor errors of the signal's size are a dead zone, a bilinear gain, a compression (tanh), a quadratic,
   clips, kinks, a wrap-around, an exponential diode leak, a jump at zero and quantisers -- none a smooth odd
   expansion);
11. mass force x the SPRING's EXTENSION through an IMPACT SAMPLE: a knock sensor on the jaw's guard triggers the tow's
    tension clamp: at each of the jaw's impacts the controller samples the cable's extension and sets a hold-back
    magnet on the carriage from its excess over z_r, held until the next impact: -F*max(0, z_k - z_r)/dz, z_k the
    extension at the scan after the latest contact from the gap began (the earlier impact samples read the slip, the
    carriage's speed and the motor's speed);
13. motor load moment x the CARRIAGE's SPEED through a PWM ACTUATOR: the drive's dynamic-braking chopper: at each PWM
    period's start (n scans of 0.2 ms) the controller samples the carriage's speed and sets the braking resistor's duty
    from its excess over the line speed v_0: duty = clip((v - v_0)/v_w, 0, 1); the resistor is switched in for the
    period's first round(duty*n) scans and loads the motor with T while in: T*m (the earlier PWM actuators read the
    wheel's speed, the extension and the slip; the earlier memories of the carriage's speed are a delay, an impact
    sample, a lag, a latch, a moving mean, an off-delay, an on-delay, a one-shot, a PI, a rattle, a rate-and-state
    state, a resonator, a run-to-run controller, a since-stroke integral, a slip hub, a step controller and a stroke
    peak -- none a PWM).
"""
