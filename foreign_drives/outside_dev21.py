"""Outside mechanisms, twenty-first DEVELOPMENT half (issue 31 part 4, set 21): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twenty sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev20`, :mod:`outside_sealed20`) have, with their laws in
the open. The twenty-first sealed half is :mod:`outside_sealed21`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (sensor,
motor load moment, clutch torque, wheel torque); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed21` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 motor load moment, 14 wheel torque). Seven of the fourteen are plain memoryless laws of new kinds,
seven have a memory of their own (here: 1, 9, 13 memoryless; 3, 5, 7, 11 with a memory; the sealed half: three with a
memory, four memoryless). Written before any diagnose, analyze or proposal ran on them (the commit history is the
proof); each strength is set by one simulation against the clean drive of the same seed, for visibility, and not
changed after. Checked before the list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2
148.2-153.9 rad/s, the slip about +-3 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s, the electromagnetic torque following
the 1.6 p.u. pulse, the pulse 60 ms every 0.25 s, the gap's half-width about 0.043-0.06 rad, the jaw free for 15-35
ms after each onset): no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's
crossings of the gap, the wheel's turns or the mains' cycle), and none is an earlier kind moved to another balance or
sensor.

Kinds (balance x what it reads, and how), the development half -- things a real drive has that nobody wrote down:

1. motor load moment x the MOTOR's SPEED through the SQUARE of its EXCESS over a threshold: a self-excited (shunt) DC
   generator on the motor's free shaft end feeding a resistor bank (a test-stand load, a field supply): below its
   critical speed Omega_c its field does not build up; above it its voltage, hence its current, grows with the excess,
   and its braking torque with the excess's square: c*max(0, Omega1 - Omega_c)^2 (the earlier laws of the motor's
   speed alone are a Lorentzian (the eighth set's fan flutter), a smooth step times its square (the ninth set's
   blower), a choked square (the twelfth set), a logarithm (the thirteenth set), a constant power (the eighth sealed
   half), an encoder's whole steps (the fifth sealed half) and, behind memories, excesses linear in a held speed; the
   squared excesses are of the carriage's speed (the first sealed half) and of the extension (the second sealed half));
3. wheel torque x the jaw's GAP DISTANCE through an ON-DELAY: an anti-runaway guard: an inductive gap sensor between
   the jaw's faces reports the faces apart by more than h_t; once that has held for T_d (a PLC's on-delay timer,
   scanned every 0.2 ms) it applies the drum's holding brake, -T, released at the first scan the faces are nearer
   (in contact included): -T*m, m = 1 while the gap distance has been above h_t at every scan for at least T_d (the
   earlier on-delays read the carriage's speed (the seventh set), the slip (the thirteenth sealed half) and the
   extension (the nineteenth sealed half); the earlier laws of the gap distance are memoryless: a squeeze film across
   the jaw (the third sealed half) and an approach brake on the motor (the fifteenth sealed half));
5. clutch torque x the jaw's ANGLE DIFFERENCE through a FIRST-ORDER RELAXATION (a Maxwell element): a viscoelastic
   rubber boot sealing the jaw bridges its halves: its stiffness k acts on the twist D less its relaxed part q, which
   creeps after D with the rubber's relaxation time tau: k*(D - q) from the motor to the wheel, q' = (D - q)/tau (q
   advanced every 0.2 ms, q = D at the run-in's start), in the gap and in contact (the earlier memories of the jaw's
   angle are a play (the fourteenth set), a stroke sample (the seventeenth set), a rate limiter (the eighteenth set),
   a Dahl element (the sixth sealed half) and a toggle (the eleventh sealed half); the fourth set's viscoelastic insert
   relaxes the contact's penetration, in contact only);
7. mass force x the CARRIAGE's SPEED through a MOVING AVERAGE: a linear booster on the carriage under a speed loop
   whose encoder reading is averaged over the last n scans of 0.2 ms (a boxcar in the loop), its force limited:
   -K*clip(m - v_r, -d, d), m the mean of v over the last n scans (all n = v at the run-in's start) (the earlier moving
   averages read the motor's speed (the tenth sealed half), the extension (the eighteenth sealed half) and the slip
   (the nineteenth set); the earlier memories of the carriage's speed are a lag, a sampled delay, a run-to-run mean,
   an impact sample, a rate-and-state, an on-delay, a step controller, a slip hub, a rattle, a resonator, a stroke
   integral and peaks held since the stroke began);
9. a1 sensor x the ELECTROMAGNETIC TORQUE TIMES a MAINS SINE: a1's signal cable shares a tray with the motor's power
   cable; the supply current's field induces a hum at the mains frequency whose amplitude follows the motor's
   torque-producing current: y = x + k*t_e*sin(2*pi*f*t + phi), t_e the motor's electromagnetic torque [p.u.], t the
   time from sample 0 (the earlier hum, the second sealed half's, has a fixed amplitude on a2; the only earlier sensor
   term of t_e is the eighteenth sealed half's pyroelectric heat lag of its square; the thirteenth set's magnet pickup
   reads the motor's speed and angle);
11. a2 sensor x the WHEEL's ANGLE through an ANGLE-TRIGGERED SAMPLE-AND-HOLD: a2's module is clocked by the drum
    shaft's encoder (an order-tracking acquisition): it samples a2 at each of the encoder's N pulses per turn and the
    recorder holds the latest sample: y[n] = x[k], k the latest sample at which floor(N*(theta2 - phi)/(2*pi)) changed,
    theta2 the wheel's angle unwrapped (y = x until the first pulse after the pre-roll's first sample) (the earlier
    holds of a sensor are a window of the motor's angle (the fourth set's telemetry shadow), the stroke (the seventeenth
    sealed half's blanking), blocks of samples (the thirteenth sealed half) and a fixed sub-rate (the fifth sealed
    half), none clocked by a shaft);
13. clutch torque x the SLIP TIMES a LORENTZIAN of the jaw's ANGLE DIFFERENCE: a vane-type rotary damper beside the
    jaw whose vanes pass a metering land at the gap's centre: the oil is throttled, and the slip damped, most while
    the halves are aligned and less as they twist apart: c*(Omega1 - Omega2)/(1 + (D/w)^2), D the jaw's angle
    difference, in the gap and in contact (the earlier dampers across the jaw are constant (the first set), switched by
    the stroke, the contact or the fill, of the motor's speed, of the extension, a squeeze film stiffening towards the
    faces while the jaw is free (the third sealed half), none greatest at the centre).
"""
