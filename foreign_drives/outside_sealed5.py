"""Outside mechanisms, fifth SEALED half (issue 31 part 4, set 5).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed5``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first four sets
nor the fifth development half (:mod:`outside_dev5`) has, and the suite's rows (seeds 8300+). The split rule is in
:mod:`outside_dev5` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed5")``), not listed in
``suites.SUITES``.

2. motor load moment x a PRODUCT of the load pulse and the motor speed: the stroke's forming load is strain-rate
   sensitive (a viscoplastic material: its flow stress rises with the ram's speed), so during a stroke the load grows
   with the motor speed, pulse*c*(Omega1 - Omega_ref);
4. wheel torque x the spring extension SAMPLED AT EACH STROKE: a strip-tension control (a dancer) reads the spring's
   extension once per stroke, at the pulse's rising edge, and sets the wheel's feed brake for the whole stroke period
   from it, -K*(z_k - z_ref), held until the next stroke;
6. clutch torque x the motor speed SQUARED times the sign of the slip: centrifugal friction shoes in the coupling, in
   parallel with the jaw; their normal force grows with Omega1^2 and they pass a dry friction torque from the faster
   half to the slower, in the gap too, c*Omega1^2*tanh((Omega1 - Omega2)/eps);
8. mass force x the carriage's own POSITION (spatially periodic, locked to neither shaft): the carriage's rail has a
   joint every L metres; each time the carriage's wheel rolls over one, over a length l, it is braked with F;
10. a1 sensor x a1 UNDERSAMPLED (aliasing): a1 comes from a module that samples at fs/M with no anti-alias filter; the
    recorder interpolates its samples linearly up to 50 kHz;
12. motor load moment x the motor speed QUANTISED (encoder counts per scan): a PLC reads the motor speed as an
    encoder's count per scan (steps of q rad/s), sampled every scan, and puts a regenerative load on the motor of K
    per whole step above a set speed;
14. wheel torque x the wheel speed TIMES the pulse through an inductor's LAG: an eddy-current brake on the wheel
    energised for each stroke; its field current follows the pulse with the coil's L/R, -c*Omega2*i, i' = (pulse - i)/tau.
"""
