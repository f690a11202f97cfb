"""Outside mechanisms, tenth SEALED half (issue 31 part 4, set 10).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed10``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first nine sets
nor the tenth development half (:mod:`outside_dev10`) has, and the suite's rows (seeds 10100+). The split rule is in
:mod:`outside_dev10` (written as one list of fourteen; the even numbers are here; 2, 10, 14 with a memory, 4, 6, 8, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed10")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a MOVING AVERAGE (a finite memory): a variable-displacement pump on
   the motor's shaft end whose displacement controller reads the motor speed through a PLC's moving-average filter
   over the last N scans (N*0.2 ms): a load K*max(0, mean_N(Omega1) - Omega_0) (every speed older than N scans
   forgotten at once: a boxcar, not an exponential lag);
4. wheel torque x the unwrapped wheel angle through a LINK-BY-LINK RANDOM pattern: a roller chain from an n-tooth
   sprocket on the wheel shaft to a conveyor; its links are unevenly worn, so each link's engagement passes a torque
   error of its own: T*u_k, u_k pseudo-random in [-1, 1) of the link count k = floor(n*theta2/(2*pi)), theta2 the wheel
   angle unwrapped from the run-in's start (a pattern as long as the chain, longer than the record: locked to the
   wheel angle, not periodic in a turn);
6. clutch torque x the motor angle at order 2, ADDITIVE: a diaphragm (disc) coupling in parallel with the jaw, mounted
   with an angular misalignment: its discs flex twice per turn and pass a torque A*sin(2*alpha1 + phi) from the motor to
   the wheel at all times (an angle-locked torque between the two halves, equal and opposite on the two shafts: not the
   catalogue's ripple on the motor, not a wheel mesh, not the third set's moving gap);
8. mass force x the time through a neighbour's STRIKES: a neighbouring press on the same floor strikes every T_n
   seconds (its own rate, not this press's); each strike rings the carriage's rail with a decaying shock at f_r:
   F*exp(-((t - t_0) mod T_n)/tau)*sin(2*pi*f_r*(t - t_0)), f_r*T_n a whole number (a train of decaying shocks of its
   own period: not a sine, not a window);
10. a2 sensor x a2's own past through a SMOOTH HYSTERESIS: a2's piezoceramic element has a ferroelectric hysteresis:
    y = a + H*s, s -> sign(da) - (sign(da) - s)*exp(-|da|/a_c) for each sample's change da of the acceleration (a
    Dahl-type, rate-independent loop of half-height H added to the reading; s = 0 at the pre-roll's first sample);
12. a1 sensor x a1 through a CROSSOVER DEAD ZONE: a1's line driver is a class-B output stage without bias: y =
    sign(a)*max(0, |a| - d) (small accelerations vanish, large ones read d short: a dead zone around zero);
14. mass force x the mass speed SAMPLED AT EACH JAW IMPACT: a knock sensor on the coupling's housing triggers the PLC to
    sample the carriage's speed at each contact from the gap (the first 0.2 ms scan after it begins) and a linear brake
    on the carriage is set from it, -K*(v_s - v_ref), held until the next impact (a sample-and-hold timed by the drive's
    own impacts, not by the stroke or an angle).
"""
