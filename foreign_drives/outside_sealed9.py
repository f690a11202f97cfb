"""Outside mechanisms, ninth SEALED half (issue 31 part 4, set 9).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed9``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first eight sets
nor the ninth development half (:mod:`outside_dev9`) has, and the suite's rows (seeds 9100+). The split rule is in
:mod:`outside_dev9` (written as one list of fourteen; the even numbers are here; 4, 10, 14 with a memory, 2, 6, 8, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed9")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed TIMES the spring extension: a magnetic-particle brake on the motor's shaft end
   is a tension control: its excitation comes from a potentiometer on the spring's bracket, so it brakes with
   c*z*Omega1 (a viscous load whose coefficient is the spring's extension: a bilinear law of two states);
4. wheel torque x a ONE-SHOT fired by the wheel angle: a cam switch at the wheel angle phi fires a timer that applies
   a solenoid brake for a fixed time W after each pass: -T while less than W seconds since the latest pass of phi
   (scanned every 0.2 ms; a brake window fixed in time, so its angular extent grows with the speed);
6. clutch torque x the jaw's angle difference beyond an INNER DEAD ZONE: rubber bumpers inside the jaw's gap touch at
   |D| = d0 < beta, before the metal faces: k_r*sign(D)*max(0, |D| - d0) from the motor to the wheel, in the gap and
   in contact (a soft stop that engages before the contact: a second, earlier, softer contact);
8. mass force x the WHEEL SPEED squared: a blower on the wheel shaft blows on a sail on the carriage: F = c*Omega2^2
   along x (a cross-balance power law: the mass pushed by the other shaft's speed);
10. a1 sensor x a1's own past through a MOUNTING RESONANCE: a1 is glued on a plastic bracket that rings: y is a
    second-order low-pass of a with natural frequency f_n and damping ratio zeta ~ 0.05 (a peak of gain ~1/(2*zeta)
    at f_n: not a well-damped anti-alias filter);
12. motor load moment x the motor angle through a RECTANGULAR WINDOW: a rotary distributor valve on the motor's shaft
    end feeds a cylinder during n windows of each turn: +T while (alpha1 - phi) mod (2*pi/n) < d*2*pi/n, else 0 (a
    square wave of the motor angle, all odd and even harmonics at once);
14. wheel torque x the wheel speed through a PEAK DETECTOR with decay: a drag-cup overspeed governor on the wheel shaft
    whose flyweights are held out by a ratchet that a dashpot lets go slowly: it brakes with -K*max(0, m - Omega_0),
    m the wheel speed's peak, decaying with time constant tau (a brake set by the recent maximum speed).
"""
