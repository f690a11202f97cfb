"""The signals a drive streams, with their SI units: one SignalChunk topic each, plant/<name>."""

SIGNAL_UNITS = {
    "a1": "m/s^2",                 # drive-wheel circumference acceleration, motor side
    "a2": "m/s^2",                 # load-mass acceleration
    "omega1": "rad/s",             # motor shaft speed
    "omega2": "rad/s",             # load-side wheel speed
    "angle_difference": "rad",     # alpha1 - alpha2 (the encoders' measurement)
}
STREAM_SIGNALS = tuple(SIGNAL_UNITS)
