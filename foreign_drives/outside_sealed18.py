"""Outside mechanisms, eighteenth SEALED half (issue 31 part 4, set 18): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev18`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the spring extension through a MOVING AVERAGE (a boxcar): a tension load cell's weighing
   indicator averages its reading over the last n 0.2 ms scans and drives an eddy-current brake on the motor's free
   shaft end with the average's excess over z_r: c*max(0, m - z_r), m the mean of z over the last n scans (all n = z at
   the run-in's start) (the tenth sealed half's boxcar is of the motor's speed, on the motor; the earlier motor loads
   of the extension are a linear excess, a staircase, the extension times the motor speed and a peak held since the
   stroke began; the earlier memories of the extension on other balances include a one-shot, a toggle, a play, a rate
   limiter, a Dahl element, a delay, a latch and a stroke sample, none an average over a window);
4. wheel torque x the wheel's angle LESS A CLOCK'S ANGLE through a SINE (a pole-slipping synchronous machine): a
   small synchronous motor, fed from the mains, is geared 1:1 to the wheel's shaft (it drives a timing unit); the wheel
   runs below its synchronous speed Omega_s, so its poles slip and its torque swings at the slip frequency:
   T*sin(p*(alpha2_u - Omega_s*(t - t_0)) + phi), alpha2_u the wheel's angle unwrapped from the run-in's start, p its
   pole pairs (the fourth sealed half's phase-lock trim reads the same angle difference through a clip, a correction
   that never slips a pole; the eleventh sealed half's magnetic coupling drives a hidden rotor on the motor; the cam
   follower and the ripples are sines of the angle alone, the floor vibration of the time alone);
6. clutch torque x the slip through a ONE-SHOT TIMER: an anti-clatter damper coupling beside the jaw, engaged by a
   solenoid that a timer holds for T_h after the slip rises through s_t (the drive half closing on the jaw fast): c*s*m,
   m -> 1 at a 0.2 ms scan where s rose through s_t (at or below it at the scan before) while m = 0, back to 0 T_h later
   (m = 0 at the run-in's start), s = Omega1 - Omega2 (the thirteenth sealed half's slip-monitored coupling is an
   on-delay of the slip, on only while the slip stays above its threshold; the earlier one-shots are of the extension,
   the motor's and the wheel's speeds, the penetration and the wheel's angle, never of the slip);
8. mass force x the jaw's CONTACT AGE through a DECAYING RINGING: each contact from the gap sends a shock along the
   cable into the carriage's tow bracket, which rings: F*exp(-a/tau)*sin(2*pi*f*a), a the time since the current
   contact began (0 in the gap) (a ringing re-started by the jaw's contacts: the tenth set's stroke torsional ring and
   the third set's stroke ringing of a2 restart at each load pulse, the tenth sealed half's neighbour press's shocks
   at a period of their own; the fourth sealed half's hydraulic cushion decays with the contact's age on the clutch,
   without ringing);
10. a1 sensor x the motor's electromagnetic torque SQUARED through a HIGH-PASS (a pyroelectric output): a1's piezo
    element sits on the motor's housing, which the stator's copper losses (~ the torque squared) warm through a thermal
    time constant tau; the element's pyroelectric charge follows the rate of its temperature: y = x + k*(e - theta)/tau,
    theta' = (e - theta)/tau, e = t_e^2 (t_e the motor's electromagnetic torque, p.u.; theta = e at the recording's
    pre-roll start) (a1 read with a part of the rate of the motor's heating: the fourth sealed half's piezo zero shift
    steps with the shocks, the catalogue's bias drifts in time, the seventh sealed half's bearing warm-up is a motor
    load; no earlier sensor reads the motor's current or torque);
12. motor load moment x the jaw's CONTACT SIDE: an inductive proximity switch at the jaw's far face switches a motor-side
    dynamic brake on while the far face is in contact (the wheel overrunning the motor): T while the contact is on the
    far side, else 0 (a motor load of the contact's side: the fifteenth sealed half's gap-approach brake reads the
    distance to the nearer face in the gap, the third sealed half's thrust bearing the contact's torque, the fifteenth
    sealed half's fill brake a fill level of the drive-side contact on the wheel, the tenth set's interlock brake the
    contact's age on the wheel);
14. wheel torque x the spring extension through an ASYMMETRIC LAG (a check valve with a bleed): a tension cylinder on
    the cable's guide sheave feeds a wheel brake's caliper through a check valve (it fills with a rise time tau_r) and a
    bleed orifice (it drains with a fall time tau_f > tau_r): -c*max(0, m - z_r), m -> z + (m - z)*exp(-dt/tau_r) while
    z > m, else z + (m - z)*exp(-dt/tau_f), every 0.2 ms (m = z at the run-in's start) (the sixteenth sealed half's
    tension-proportional brake on the wheel has no memory; the earlier memories of the extension on the wheel are a
    latch, a stroke sample, a play and a peak held since the stroke began; the earlier asymmetric lags are of the
    wheel's speed, on the motor, and of the carriage's speed, on the carriage).
"""
