"""Outside mechanisms, fifteenth SEALED half (issue 31 part 4, set 15): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev15`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the motor speed through a PI CONTROLLER with a BRAKE-ONLY output: a speed-limiting eddy-current
   brake on the motor's shaft under a digital PI controller, u = K_p*e + I, e = Omega1 - Omega_ref, I += K_i*e*dt
   unless u is at a limit and e pushes it further (clamping anti-windup), u limited to [0, T_max], scanned every 0.2 ms
   (I = 0 at the run-in's start); u on the motor's load (the sixth set's PI brake reads the wheel speed for the
   wheel; the earlier memories of the motor speed on the motor are lags, a play, a rate limit, a moving mean, a peak,
   a one-shot, a step controller, a heat, a slip hub, a magnetic coupling, an absorber);
4. wheel torque x the jaw's DRIVE-FACE CONTACT through a FILL: a hydraulic drag brake on the wheel whose cylinder a
   pump fills while a contact switch on the jaw's drive faces is closed and which empties through a return orifice
   otherwise: -T*m, m += dt/T_f while the drive faces touch, m -= dt/T_d otherwise, clamped to [0, 1] (scanned every
   0.2 ms; m = 0 at the run-in's start) (a level integrated up and down by the jaw's own contact: the tenth set's
   interlock brake rises afresh from each contact's start and drops in the gap, the eleventh sealed half's fill follows
   the load pulse);
6. clutch torque x the slip through a THERMAL memory of its own dissipation: a viscous (silicone) coupling beside the
   jaw whose fluid thins as it heats, Reynolds' law: c*(Omega1 - Omega2)*exp(-theta/theta_c), theta += dt*(a*(Omega1 -
   Omega2)^2 - theta/tau) every 0.2 ms (theta = 0 at the run-in's start) (the first set's gap drag is this coupling
   cold; the fifth set's insert heating softens the contact law with the contact's power, the seventh sealed half's
   warm-up thins the motor bearings' grease with the motor speed, the tenth set's cut-out switches a wheel brake);
8. mass force x the spring extension through a DAHL element: the spring's cable is a stranded wire rope whose strands
   rub on each other as it stretches and slackens (taken at the cable guide on the carriage): F_f*s along x, s ->
   sign(dz) - (sign(dz) - s)*exp(-|dz|/z_c) for each change dz of the extension over a 0.2 ms scan (s = 0 at the
   run-in's start) (a rate-independent friction of the extension's direction: the sixth set's Dahl ring is across the
   jaw, the twelfth set's lost-motion link is a play with a linear slot, the ninth set's cable friction follows the
   carriage's speed);
10. a1 sensor x a1's own past through a FIXED LATENCY: a1's rotating telemetry buffers d samples before it sends
    them, so the recorded a1 is the signal d samples earlier: y[n] = x[n - d] (x[0] before the pre-roll's first
    sample) (a pure delay of one channel: the sixth set's jitter is random, the fourth sealed half's clock lag grows,
    the twelfth set's echo adds a delayed copy to the signal);
12. a2 sensor x the MOTOR SPEED, additive: a2's signal return shares a wire with the motor's tacho-generator, whose
    output (zeroed by the drive's bias at Omega_0) drops across it: y = x + k*(Omega1 - Omega_0) (the thirteenth set's
    magnet pickup is locked to the motor's angle and only scaled by its speed; the fourteenth set's velocity
    sensitivity reads the carriage's speed; the first sealed half's centripetal term is a1's, of Omega1 squared);
14. motor load moment x the jaw's GAP DISTANCE through a CUSHION: an approach brake: an inductive gap sensor between
    the jaw faces feeds an eddy-current brake on the motor while the halves are apart, the harder the nearer a face:
    c*(h_0/(h + h_0))^n, h the distance to the nearer face, 0 while the faces touch (the third sealed half's squeeze
    film is a clutch torque of the slip times such a factor; no earlier motor load reads the jaw's geometry but through
    the contact torque).
"""
