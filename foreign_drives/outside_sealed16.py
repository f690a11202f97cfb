"""Outside mechanisms, sixteenth SEALED half (issue 31 part 4, set 16): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev16`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the motor speed SAMPLED AT EACH STROKE's START: a flywheel-energy controller: at each load
   pulse's first 0.2 ms scan the PLC reads the motor speed and sets a generator brake on the motor's shaft for the
   whole stroke and the pause after it: c*max(0, S - Omega_0), S the sample (S = Omega1 at the run-in's start) (the
   fifth sealed half's stroke sample is of the extension, for the wheel; the earlier memories of the motor speed on
   the motor are lags, a play, a relay, a rate limit, a moving mean, a peak, a one-shot, a step controller, an
   unloader, a heat, a slip hub, a magnetic coupling, an absorber, a PI controller; none samples it per stroke);
4. wheel torque x the spring extension through a PLAY: a slack Bowden cable from the spring's cable guide to a band
   brake's lever on the wheel: the lever's position m follows the extension only once the slack 2a is taken up, m ->
   min(max(m, z - a), z + a) every 0.2 ms (m = z at the run-in's start), and the brake pulls -c*max(0, m - z_0) (the
   twelfth set's lost-motion link is a play of the extension with a friction on the carriage; the fourteenth sealed
   half's latch and the fifteenth set's ratchet brake the wheel from the extension with other memories; the third
   set's governor linkage play is of the motor speed on the motor);
6. clutch torque x the slip TIMES the motor speed through a LAG: an electromagnetic slip coupling beside the jaw whose
   field coil is fed from the motor's tacho-generator; the coil's inductance lags the excitation behind the speed:
   c*max(0, m - Omega_0)*(Omega1 - Omega2), m -> Omega1 + (m - Omega1)*exp(-dt/tau) every 0.2 ms (m = Omega1 at the
   run-in's start) (the twelfth sealed half's damper is gated by the motor speed without memory, the fifth sealed
   half's centrifugal shoes follow Omega1 squared at once; the earlier memories of the slip coupling are a dead time,
   an on-delay, an off-delay of the penetration, a heat, a fill of the pulse);
8. mass force x the LOAD PULSE through an IMPULSE RELAY (a toggle): a stroke divider: an impulse relay flips at each
   stroke's start and clamps a drag shoe on the carriage on every other stroke: -F*m, m -> 1 - m each time the pulse
   comes on (scanned every 0.2 ms; m = 0 at the run-in's start) (a force alternating stroke by stroke: the tenth set's
   impulse relay is toggled by the extension, the thirteenth sealed half's by the wheel speed; the n-th stroke pierce
   counts strokes with a modulus, on the motor);
10. a2 sensor x a2's own past through an AC COUPLING: a2's module has a DC-blocking input (a series capacitor into its
    input resistance, corner f_c): y[n] = q*(y[n-1] + x[n] - x[n-1]), q = exp(-2*pi*f_c/fs) (y = 0 at the pre-roll's
    first sample) (a first-order high-pass of the signal: the fifth set's auto-zero subtracts a held mean at set times,
    the median and the mains notch are other filters, the mounting resonance and the smoothing are low-passes);
12. wheel torque x the spring extension through a SIGMOID: a tension-limiting pneumatic brake on the wheel, fed by a
    proportional valve that a lever on the spring's cable opens smoothly about z_s: -T*(1 + tanh((z - z_s)/w))/2 (a
    smooth step of the extension on the wheel: the rope drum's layers step with the wheel's angle, the latch and the
    ratchet hold, the overload band brake is a linear excess on the motor);
14. clutch torque x the slip through a DEAD BAND: a vane damper beside the jaw whose vanes leak through a bypass up to
    a slip s_0 and damp beyond it: c*sign(s)*max(0, |s| - s_0), s = Omega1 - Omega2 (a viscous law of the slip with a
    dead band: the earlier slip couplings are linear from zero, overrunning (one-sided), hydrodynamic, gated or with a
    memory; the ninth sealed half's dead zone is of the jaw's angle, rubber bumpers).
"""
