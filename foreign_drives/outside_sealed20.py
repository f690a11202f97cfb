"""Outside mechanisms, twentieth SEALED half (issue 31 part 4, set 20): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev20`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the SPRING EXTENSION through a PWM ACTUATOR: a tension controller pulses a motor-side eddy
   brake through an on/off valve: at the start of each period of n 0.2 ms scans it takes the duty clip((z - z_0)/w,
   0, 1) from the extension and keeps the valve open for the first round(duty*n) scans of the period: T*m, m = 1
   while open, else 0 (the period starts at the run-in's first scan) (the sixth set's PWM brake reads the wheel's
   speed, on the wheel; the earlier memories of the extension on the motor are a peak held since the stroke began
   (the sixteenth set), an off-delay (the seventeenth sealed half) and a boxcar (the eighteenth sealed half));
4. wheel torque x the CARRIAGE's SPEED through a THREE-POINT STEP CONTROLLER: a line-speed controller trims the drum's
   brake through a motorised valve: one step up each T_s the carriage's speed stays above v_r + d, one step down each
   T_s it stays below v_r - d, between 0 and N steps: -T*m, m the steps (m = 0 at the run-in's start; the scans
   counted every 0.2 ms) (the eighth sealed half's step controller reads the motor's speed, on the motor; the earlier
   memory of the carriage's speed on the wheel is the eighteenth set's peak held since the stroke began);
6. clutch torque x the SLIP through a SELF-EXCITED OSCILLATOR: the felt dust seal between the jaw halves squeals when
   the drive half overruns the wheel: a van der Pol oscillator of its own frequency f whose negative damping grows with
   the slip's excess over s_c: T*X/2, X'' = w*g*(s - s_c)*(1 - X^2)*X' - w^2*X, w = 2*pi*f, s = Omega1 - Omega2 (X =
   1e-3, X' = 0 at the run-in's start; a floor keeps a seed amplitude), in the gap and in contact (the earlier squeals
   are of the wheel's speed, on the wheel (the eighth set), and of the extension, on the carriage (the nineteenth
   sealed half); the earlier memories of the slip across the jaw are a lag, a tank, a delay, an on-delay, an off-delay,
   a heat integrator, a one-shot, a rate limiter and a thermal cut-out);
8. mass force x the SPRING EXTENSION through a TANK: the cable's tension cylinder is a piston pump the cable's pull
   works: it fills the carriage's hold-back cylinder at a flow a*z, which drains through an orifice, b*sqrt(h): -F*h,
   h' = a*z - b*sqrt(h), h >= 0 (h = 0 at the run-in's start) (the earlier tanks are filled by the wheel's speed (the
   twelfth set, on the wheel), the slip (the thirteenth set, across the jaw) and the pulse (the eighth sealed half, on
   the carriage); the earlier memories of the extension on the carriage are a toggle, a play, a stroke sample, a
   rate limiter, a delay, a Dahl element, a one-shot and a squeal);
10. a2 sensor x a BASELINE RESTORER (a one-sided envelope follower): a2's module has a DC restorer, a clamp as in
    pulse electronics: its baseline b follows the signal's lower envelope, taking any sample below it at once and
    creeping up at R otherwise, and is subtracted: b[n] = min(x[n], b[n-1] + R/fs), y = x - b (b = x at the
    pre-roll's first sample) (the earlier zero-setting memories of a sensor are a periodic tare of the mean (the fifth
    set's autozero), a first-order high-pass (the third and sixteenth sealed halves) and a play (the ninth set's loose
    seismic mass, two-sided and not subtracted));
12. mass force x the TIME SINCE THE LATEST STROKE BEGAN through a WINDOW at a set delay: the press's strip gripper
    grips the strip from d to d + w after each stroke began; the strip, threaded through the carriage's guide, holds
    the carriage back while it is gripped: -F while d <= t - t_s < d + w, else 0, t_s the latest load pulse's start,
    on or off (the third set's pneumatic hold-back on the carriage rises after a delay and holds to the next stroke;
    the sixteenth set's flying shear is a smooth peak while the pulse is on, on the motor; the nineteenth set's pump
    is a ramp held at its top, on the motor);
14. clutch torque x the jaw's ANGLE DIFFERENCE through a SIGN (a preload): a pre-compressed centring spring cartridge
    across the jaw pushes back by its preload T_0 as soon as the jaw leaves its centre, whichever way: -T_0*tanh(D/w),
    w a small smoothing angle, D the jaw's angle difference, in the gap and in contact (the earlier laws of the jaw's
    angle alone are linear, a power, a sine (the eighth set's ball detent), a face pull (the seventh set), a dead zone
    (the ninth sealed half's bumpers) and a snap-through of the overlap (the ninth set), none a constant torque).
"""
