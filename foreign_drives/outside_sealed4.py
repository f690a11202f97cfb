"""Outside mechanisms, fourth SEALED half (issue 31 part 4, set 4).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed4``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first three
sets nor the fourth development half (:mod:`outside_dev4`) has, and the suite's rows (seeds 8100+). The split rule is
in :mod:`outside_dev4` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed4")``), not listed in
``suites.SUITES``.

2. motor load moment x the motor speed through a LAG (a hidden state): an auxiliary flywheel (a feed pump's rotor,
   a large fan impeller) driven from the motor shaft by V-belts whose creep is proportional to the torque they pass:
   the belts load the motor with c*(Omega1 - w_f), the flywheel's speed w_f following Omega1 with tau = J_f/c;
4. wheel torque x the wheel speed DELAYED, beyond a limit: an overspeed guard; a PLC reads the wheel speed over a
   fieldbus and applies an eddy-current brake -k*max(0, Omega2(t - d) - Omega_lim), d the bus's and the PLC's dead
   time;
6. clutch torque x the TIME SINCE THE CONTACT BEGAN: hydraulic cushions behind the jaw faces; at each contact their
   chambers are compressed and empty through an orifice, so the cushion adds k_h*p at first and fades as it empties,
   k_h*p*exp(-t_c/tau); they refill in the gap;
8. mass force x RANDOM INSTANTS (a Poisson process, locked to nothing of this drive): the neighbouring station's
   pneumatic kicker, on the same rail and air supply, fires on its own irregular cycle; each firing pushes the
   carriage back with F for T_p;
10. a1 sensor x a1's OVERLOADS with memory: a1 is piezoelectric; accelerations beyond its linear range leave a
    residual charge (a zero shift, signed with the overload) that the charge amplifier bleeds off with its time
    constant: b' = kappa*(max(0, a - a_s) - max(0, -a - a_s)) - b/tau, a1 += b;
12. a2 sensor x TIME as a growing lag: a2 is digitised by a separate I/O module whose sample clock runs slow against
    the recorder's: the recorded a2 at t is the signal at t - g*t (a lag growing by g per second);
14. wheel torque x the wheel ANGLE against a CLOCK, saturating: an electronic line shaft; a trim drive keeps the wheel
    in phase with the line's master clock, -K*sat(theta2 - Omega_ref*t - theta0, T_max/K), theta2 the wheel angle
    unwrapped from the run-in's start.
"""
