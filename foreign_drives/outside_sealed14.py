"""Outside mechanisms, fourteenth SEALED half (issue 31 part 4, set 14): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev14`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the WHEEL speed through a LAG with a rise and a fall time: a hydraulic brake on the motor's
   shaft fed from a gear pump on the wheel's shaft through a long line and a check valve: its pressure follows Omega2
   with time constant tau_r rising and tau_f falling (every 0.2 ms; m = Omega2 at the run-in's start), the brake
   loading the motor by c*m (a load on one shaft from the other shaft's lagged speed: the earlier lags act on the same
   shaft's balance or on the mass);
4. wheel torque x the SPRING EXTENSION through a LATCH reset at each stroke: a limit switch on the spring's cable
   guide trips once the extension exceeds z_t and latches a brake on the wheel, -T, until the next load pulse's start
   resets it (scanned every 0.2 ms; the seventh set's stroke-reset latch reads the wheel speed);
6. clutch torque x the slip speed, switched by an OFF-DELAY on the jaw's penetration: a proximity switch sees the jaw's
   faces in contact (penetration depth above p_t) and engages an electromagnetic coupling beside the jaw, held for T_h
   after the last scan in contact (a run-on timer): c*(Omega1 - Omega2) while engaged (the eleventh set's off-delay
   reads the wheel speed for a wheel brake, the thirteenth set's on-delay the slip itself);
8. mass force x the spring extension through a DEAD TIME: a pneumatic hold-back cylinder on the carriage servoed on a
   cable-position sensor whose value crosses a slow fieldbus: -k*(z(t - T_d) - z_0), z sampled every 0.2 ms (a spring
   to a delayed copy of the extension: the earlier dead times read the speeds or the slip);
10. a1 sensor x a1's own past through an ASYMMETRIC LAG: a1's output stage follows its input with time constant
    tau_r while the input is above the output and tau_f while below (a peak-detector-like stage with a slow discharge)
    (a dynamic, amplitude-dependent distortion: the fourth set's slew limiter moves at a bounded rate, the catalogue's
    low-passes are linear);
12. a2 sensor x the SAMPLE INDEX: a2's converter interleaves two ADCs, even samples on one, odd on the other, with a
    gain and an offset mismatch: y[k] = x[k]*(1 + g*(-1)^k) + o*(-1)^k (a tone at half the sample rate and a mirror
    of the signal about it: the earlier time-locked interferences are sinusoids or a gain ripple at a set frequency);
14. mass force x the spring extension through a LOCALISED PEAK: a permanent magnet on the cable guide pulls on a steel
    clamp on the spring's cable as it passes: F/(1 + ((z - z_m)/w)^2) along x (a force concentrated near one
    extension: the earlier laws of the extension are powers, a periodic detent, a ramp or sampled).
"""
