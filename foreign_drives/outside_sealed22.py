"""Outside mechanisms, twenty-second SEALED half (issue 31 part 4, set 22): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev22`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the WHEEL's SPEED through a MOVING AVERAGE: a digital overspeed brake on the motor's free shaft
   end whose drum tacho is read as the boxcar mean of its last n scans of 0.2 ms; the brake grows with the mean's
   excess over a trip speed: c*max(0, m - Omega_t), m the mean of Omega2 over the last n scans (all n = Omega2 at the
   run-in's start) (the earlier moving averages read the motor's speed, the extension, the slip and the carriage's
   speed; the earlier memories of the wheel's speed are a delay, a lag, a latch, an off-delay, a one-shot, a peak, a
   PI controller, a PWM, a rattle, a squeal, a tank, a thermostat, a toggle and, through the relay, a relay -- none a
   boxcar);
4. wheel torque x the SPRING's EXTENSION through a HYPERBOLIC TANGENT: a band brake on the drum tightened by the tow
   cable's tension through a lever and a spring pack that saturates: -T*tanh(z/z_s), z the spring's extension (the
   earlier laws of the extension are linear, clipped, an excess, a Lorentzian, a smooth step between two plateaus, a
   sine and a staircase -- none a tanh through zero);
6. clutch torque x the JAW's PENETRATION DEPTH through a TANK (an orifice's square-root drain): a grease pocket behind
   the jaw's faces: each penetration pumps grease into it at a rate a*p (p the penetration on either side, 0 free);
   it drains through a bleed orifice, h' = a*p - b*sqrt(h) (h >= 0, scanned every 0.2 ms, h = 0 at the run-in's
   start); its pressure ~ h squeezes a film across the halves that damps the slip: c*h*(Omega1 - Omega2) from the
   motor to the wheel (the earlier memories of the penetration depth are a lag, an off-delay, a one-shot and a peak;
   the earlier tanks are filled by the slip, the wheel's speed, the pulse and the extension);
8. mass force x the CARRIAGE's POSITION through a TRAIN of DECAYS: rail joints every L along the carriage's track:
   each joint's step knocks the carriage back and the shock decays over a distance x_d as it rolls on:
   -F*exp(-((x - x_0) mod L)/x_d), x the carriage's position (the earlier laws of the position are sines, a half-wave
   sine, a window, a residue (a sawtooth) and a random section pattern; the earlier trains of decays are of the time);
10. a1 sensor x a RANDOM TELEGRAPH PROCESS (popcorn noise): a1's charge amplifier's input transistor has a trap that
    switches its offset between 0 and b at random: the dwell times in each state are exponential, mean tau_0 in the
    low state and tau_1 in the high one (numpy default_rng(seed): its exponentials in turn, the first dwell low,
    counted from the pre-roll's first sample): y = x + b*s(t), s the state (the earlier random sensor errors are bit
    errors, jitter and packet loss; the earlier random patterns locked to a counter or a step are hashes; none a
    two-state Markov process);
12. a2 sensor x the ELECTROMAGNETIC TORQUE through a GAIN: a2's ratiometric sensor and its converter share a supply
    whose voltage the motor's current pulls down (one transformer): the sensor's output follows its supply but the
    converter's reference is stabilised, so a2 reads low in proportion to the motor's torque: y = x*(1 - k*t_e), t_e
    the motor's electromagnetic torque [p.u.] (the earlier sensor terms of t_e are an additive hum (the twenty-first
    set) and a pyroelectric heat lag; the earlier sensor gains are modulated by the extension, by a1, by the time and
    by the process -- none by the torque);
14. wheel torque x the WHEEL's SPEED through a LOGARITHM: a grease-packed labyrinth seal on the drum's shaft whose
    shear-thinning (Eyring) grease's drag grows with the logarithm of the speed: -T*ln(Omega2/Omega_0) (0 at or below
    0) (the earlier logarithms are of the motor's speed (the thirteenth set), of the carriage's speed and of a held
    speed; the earlier laws of
    the wheel's speed on the wheel are viscous, staged, a relief valve's clip, a bypass's dead zone, a sigmoid, a
    resonance and, behind memories, many -- none a logarithm).
"""
