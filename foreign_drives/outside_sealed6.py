"""Outside mechanisms, sixth SEALED half (issue 31 part 4, set 6).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed6``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first five sets
nor the sixth development half (:mod:`outside_dev6`) has, and the suite's rows (seeds 8500+). The split rule is in
:mod:`outside_dev6` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed6")``), not listed in
``suites.SUITES``.

2. motor load moment x the load pulse times a STROKE-TO-STROKE random variation: the blanks of a batch vary in
   thickness, so each stroke's forming load differs from the last: pulse*T*u_k, u_k a pseudo-random number in [-1, 1]
   drawn from the stroke's number k (a cycle-to-cycle variation locked to nothing but the count);
4. wheel torque x the wheel speed through a PI CONTROLLER with a SATURATED actuator: a web-speed controller brakes the
   wheel with an eddy-current brake, u = K_p*e + I, e = Omega2 - Omega_ref, I' = K_i*e, u limited to [0, T_max] and I
   frozen while u is at a limit and e pushes it further (clamping anti-windup); -u on the wheel (scanned every 0.2 ms);
6. clutch torque x the jaw's angle difference through a DAHL friction element: a preloaded friction ring (an O-ring
   damper) between the jaw halves; for small relative turns it is a spring, beyond it slides at T_f, with a memory of
   where it last slid: T_f*s, s -> sign(dD) - (sign(dD) - s)*exp(-|dD|/theta_c) for each change dD of the jaw's angle
   difference (rate-independent, smooth);
8. mass force x the spring extension through a RATE LIMITER: a pneumatic balancer on the carriage whose pressure
   regulator follows the spring's extension, -K*(m - z_ref), m -> z but moving at most R (m/s) (a proportional valve
   that slews: the force lags only where the extension changes fast);
10. a1 sensor x a1 at RANDOM LATENCIES: a1's rotating telemetry sends packets whose latency varies; the recorder stamps
    them on arrival, so each recorded a1 sample is the signal at t - d_n, d_n pseudo-random in [0, D] for each sample
    (linear interpolation): a timing jitter;
12. motor load moment x the motor speed through a HIDDEN INTEGRATOR and an UNLOADER: a pump on the motor shaft charges
    the press's accumulator; its pressure p integrates the pump's flow (proportional to Omega1 while loading) less the
    press's use at each stroke; an unloader valve switches the pump off (idling) when p rises above p_high and back
    on below p_low; while on it loads the motor with D*p (a limit cycle of its own period);
14. mass force x the mass speed through a SLACK TOW CHAIN: the carriage tows a trailer cart by a chain with slack L;
    the cart's rolling resistance slows it until the chain snatches taut (a stiff, damped one-sided contact), pulls
    it up to speed and goes slack again: the carriage feels the chain's snatch loads only.
"""
