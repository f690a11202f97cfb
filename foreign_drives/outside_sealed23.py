"""Outside mechanisms, twenty-third SEALED half (issue 31 part 4, set 23): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev23`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the MOTOR's SPEED through an IMPACT SAMPLE: a knock sensor on the coupling's guard triggers the
   drive's controller at each of the jaw's impacts: it samples the motor's speed then and sets a regenerative brake
   from its excess over a trip speed, held until the next impact: c*max(0, Omega_k - Omega_t), Omega_k the motor's
   speed at the scan after the latest contact from the gap began (the earlier impact samples read the slip and the
   carriage's speed; the earlier memories of the motor's speed are a delay, a heat, a lag, a magnetic coupling, a
   moving mean, a one-shot, a peak, a PI, a play, a rate limiter, a resonator, a since-stroke integral, a slip hub, a
   step controller, a stroke sample and an unloader -- none an impact sample);
4. wheel torque x the WHEEL's SPEED through an INVERSE POWER (a cushion law): a spring-applied, centrifugally released
   holding brake on the drum: flyweights lift its shoes as the drum speeds up, so its drag falls with the speed:
   -T*(Omega_s/(Omega2 + Omega_s))^n for Omega2 >= 0, else 0 (the earlier laws of the wheel's speed
   on the wheel are viscous, staged, a relief valve's clip, a bypass's dead zone, a sigmoid, a logarithm, a tanh and,
   behind memories, many -- none falling with the speed; the earlier falling laws are of the motor's speed, a power);
6. clutch torque x the JAW's PENETRATION DEPTH through a LATCH reset by the STROKE, TIMES the SLIP: an electromagnetic
   lock-up coupling beside the jaw latched on by a proximity switch once the jaw has bottomed deeper than p_t, released
   at each load pulse's start: c*m*(Omega1 - Omega2), m = 1 from the first scan with p > p_t until the next stroke's
   first scan, else 0 (the earlier latches read the slip, the wheel's speed, the carriage's speed and the extension;
   the earlier memories of the penetration depth are a lag, an off-delay, a one-shot, a peak and a tank);
8. mass force x the WHEEL's ANGLE through a TRAIN of DECAYS: the cable's anchor clamp on the drum passes the fairlead
   once a turn and jerks the tow cable; the jerk on the carriage decays as the drum turns on: -F*exp(-((alpha2 - phi)
   mod 2*pi)/theta_d) (the earlier laws of the wheel's angle on the carriage are a cosine, a rectangular window and
   sines; the earlier trains of decays are of the time and of the motor's angle);
10. a1 sensor x the SIGNAL through a BLOCK-FLOATING-POINT CODEC: a1's telemetry sends blocks of N samples with one
    shared exponent each: the block's range is the smallest of F, F/2, ..., F/2^J that holds its peak, and each sample
    a mantissa of m bits in it: y = clip(round(x/q_k), -2^(m-1), 2^(m-1) - 1)*q_k, q_k = R_k/2^(m-1), blocks from the
    pre-roll's first sample (the earlier converters are fixed quantisers, a non-uniform quantiser, an adaptive delta
    modulator, a sigma-delta loop and a block average -- none a step set by each block's peak);
12. a2 sensor x the SIGNAL's SIGN: a2's converter works in sign-magnitude: a precision rectifier takes the magnitude,
    a unipolar converter digitises it and the sign is put back after; the magnitude path's offset d adds with the
    sign: y = x + d*sign(x) (the earlier memoryless sensor errors of the signal's size are a dead zone (small readings
    vanish), a bilinear gain, a compression, a quadratic, clips, kinks, a wrap-around and quantisers -- none a jump at
    zero);
14. mass force x the SPRING's EXTENSION through an INVERSE SQUARE: the tow cable sags under its own weight; the sag
    takes up a part of the extension, the more the slacker the cable, so the pull on the carriage falls short of the
    spring's by F*(z_0/z)^2 (the earlier laws of the extension on the carriage are linear, clipped, an excess, a
    Lorentzian, a sine and, behind memories, many -- none an inverse power).
"""
