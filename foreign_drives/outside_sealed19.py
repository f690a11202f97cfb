"""Outside mechanisms, nineteenth SEALED half (issue 31 part 4, set 19): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev19`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the SLIP through a LATCH RE-ARMED AT EACH STROKE: a closing-speed guard: a slip monitor trips
   a motor-side brake once the slip rises past s_t (the drive half closing on the jaw fast) and the press's valve
   releases it at the next stroke's start: T*m, m -> 0 at each load pulse's first 0.2 ms scan, then m -> 1 at a scan
   with s > s_t (m = 1 at the run-in's start if s > s_t), s = Omega1 - Omega2 (the earlier latches are of the wheel's
   speed (the seventh set), of the extension (the fourteenth sealed half) and of the carriage's speed (the eighteenth
   set); the fifteenth set's motor load of the slip is memoryless (|s|); the earlier memories of the slip include a
   lag, a fill, a delay, a tank, an on-delay, an off-delay, a heat integrator, an impact sample, a decaying peak and a
   rate limiter, none a latch);
4. wheel torque x the spring extension through an ON-DELAY (a debounced switch): a tension switch on the cable's guide
   sheave applies a wheel brake through a PLC timer once the extension has stayed above z_t for T_d: -T*m, m = 1 while
   z > z_t has held for at least T_d (counted in 0.2 ms scans), else 0 (the earlier on-delays are of the carriage's
   speed (the seventh set) and of the slip (the thirteenth sealed half); the earlier memories of the extension on the
   wheel include a latch, a stroke sample, a play and a peak held since the stroke began; the seventeenth sealed half's
   motor brake of the extension is an off-delay, on at once and held after);
6. clutch torque x the slip through a THERMAL CUT-OUT: an eddy-current drag coupling beside the jaw whose drum carries
   a bimetal cut-out: its heat h, fed by the coupling's own power while it is on and cooling with a time constant,
   switches its excitation off above h_hi and on again below h_lo: c*s*m, h' = m*c*s^2 - h/tau, m -> 0 when h > h_hi,
   -> 1 when h < h_lo (m = 1, h = 0 at the run-in's start), s = Omega1 - Omega2, in the gap and in contact (the tenth
   set's thermal cut-out is of the wheel's speed, on the wheel; the earlier slip couplings switched by a memory of the
   slip include an on-delay (the thirteenth sealed half); the fifteenth sealed half's coupling thinned by its
   heat fades smoothly, without a switch);
8. mass force x the spring extension through a SELF-EXCITED OSCILLATOR: the carriage's guide shoe squeals (a
   friction-induced vibration) when the cable's pull presses it hard: a van der Pol oscillator of its own frequency f
   whose negative damping grows with the extension's excess over z_c: F*X, X'' = w*g*(z - z_c)*(1 - X^2)*X' - w^2*X,
   w = 2*pi*f (X = 1e-3, X' = 0 at the run-in's start; a floor keeps a seed amplitude) (the eighth set's squeal is of
   the wheel's speed, on the wheel; the thirteenth sealed half's and the fifth set's resonators are driven, not
   self-excited; the earlier laws of the extension on the carriage are memoryless or a rate limiter, a delay, a toggle,
   a play, a stroke sample, a one-shot and a Dahl element);
10. a1 sensor x the TIME BASE through a CLOCK SKEW (a sample clock of its own): a1 is digitised by the motor drive's own
    converter, whose crystal runs fast by a fraction e against the recorder's clock; the recording is a1 read at the
    converter's instants: y(t) = x(t_0 + (1 + e)*(t - t_0)), t_0 the recording's first sample (the pre-roll's) (a delay
    that grows over the recording: the fifteenth sealed half's delay of one channel is constant; the earlier sensor
    timing errors are a hold, a decimation and the pulse-synchronous holds, none a drift of the time base);
12. mass force x the STROKE COUNT through a SINE: the strip is drawn from an eccentric coil, each stroke drawing the
    same length; the coil turns once every N strokes and its eccentricity swings the strip's back-tension on the
    carriage stroke by stroke: F*sin(2*pi*k/N + phi), k the current load pulse's number (a force on the carriage that
    steps once per stroke along a slow sine: the sixth set's staircase of the stroke count resets every N strokes; the
    sixth sealed half's blank thickness is a random pattern of the count, on the motor; the fourth set's sub-harmonic
    is a window of the count, on the motor);
14. clutch torque x the slip times the MOTOR SPEED's EXCESS: a centrifugal shoe clutch in parallel with the jaw: its
    shoes, on the drive half's hub, press on a drum on the wheel's half with the centrifugal force less their springs'
    pull, so the friction's capacity grows with the motor speed's excess over its engagement speed: mu*max(0, Omega1 -
    Omega_e)*tanh(s/w), s = Omega1 - Omega2, in the gap and in contact (the earlier dry frictions across the jaw are
    pressed by the cable (the sixteenth set) or by the slip's own fill (the thirteenth set), or constant (the
    thirteenth set's hysteresis coupling); the twelfth set's hydrodynamic coupling is the slip times the motor's speed,
    viscous).
"""
