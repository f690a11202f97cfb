"""Process faults without ROS: the supervisor names a child that died and restarts it by policy;
children die with their parent, also when the parent is killed with SIGKILL (prctl death signal,
and the watchdog where that is missing)."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from backlash_monitor.process.parent_watch import PARENT_PID_ENV
from backlash_monitor.process.subscriber_wait import TopicState, missing, parse_wanted
from backlash_monitor.process.supervisor import Supervisor, describe_exit
from process_fault_helpers import gone, wait_until

SLEEPER = [sys.executable, "-c", "import time; time.sleep(60)"]


@pytest.fixture
def supervisors():
    made = []
    yield made.append
    for sup in made:
        sup.stop(grace_s=2.0)


@pytest.mark.process
def test_exit_descriptions_name_the_signal_or_the_code():
    assert describe_exit(-signal.SIGKILL) == "was killed by signal SIGKILL (9)"
    assert describe_exit(-signal.SIGSEGV) == "was killed by signal SIGSEGV (11)"
    assert describe_exit(3) == "exited with code 3"


@pytest.mark.process
def test_without_restarts_a_killed_child_is_named_and_ends_the_run(supervisors):
    sup = Supervisor({"windowing": SLEEPER, "denoise": SLEEPER}, restart="no")
    supervisors(sup)
    sup.start()
    assert sup.poll() == [] and sup.failed is None
    victim = sup.pids()["windowing"]
    os.kill(victim, signal.SIGKILL)
    assert wait_until(lambda: sup.children["windowing"].process.poll() is not None)
    faults = sup.poll()
    assert [f.node for f in faults] == ["windowing"]
    assert sup.failed is faults[0]
    assert faults[0].describe() == f"node windowing (pid {victim}) was killed by signal SIGKILL (9)"
    assert sup.children["denoise"].process.poll() is None     # the other one is not touched


@pytest.mark.process
def test_on_failure_restarts_up_to_the_limit_then_ends_the_run(supervisors):
    sup = Supervisor({"classifier": SLEEPER}, restart="on-failure", max_restarts=1)
    supervisors(sup)
    sup.start()
    first = sup.pids()["classifier"]
    os.kill(first, signal.SIGKILL)
    assert wait_until(lambda: bool(sup.poll()))
    assert sup.failed is None
    second = sup.pids()["classifier"]
    assert second != first and sup.faults[0].restarted_pid == second
    assert sup.children["classifier"].process.poll() is None      # running again
    os.kill(second, signal.SIGKILL)
    assert wait_until(lambda: bool(sup.poll()))
    assert sup.failed is not None and sup.failed.pid == second and sup.failed.restarted_pid is None


@pytest.mark.process
def test_a_refused_parameter_is_not_restarted_and_a_finished_stream_is_no_fault(supervisors):
    sup = Supervisor({"plant_simulator": [sys.executable, "-c", "pass"],
                      "windowing": [sys.executable, "-c", "raise SystemExit(2)"]},
                     restart="on-failure", finishing=("plant_simulator",))
    supervisors(sup)
    sup.start()
    assert wait_until(lambda: all(c.process.poll() is not None for c in sup.children.values()))
    faults = sup.poll()
    assert [f.node for f in faults] == ["windowing"] and faults[0].restarted_pid is None
    assert sup.failed is faults[0] and "exited with code 2" in faults[0].describe()
    assert sup.finished("plant_simulator") and not sup.finished("windowing")


@pytest.mark.process
def test_bad_policies_are_refused():
    with pytest.raises(ValueError, match="allowed: no, on-failure"):
        Supervisor({}, restart="always")
    with pytest.raises(ValueError, match="max_restarts"):
        Supervisor({}, max_restarts=-1)


# A parent that starts two children, prints their pids and waits to be killed.
_PARENT = textwrap.dedent("""
    import os, subprocess, sys, time
    from backlash_monitor.process.supervisor import Supervisor
    from backlash_monitor.process.parent_watch import PARENT_PID_ENV
    child = [sys.executable, "-c", sys.argv[2]]
    if sys.argv[1] == "supervisor":         # prctl death signal (and the watchdog variable)
        sup = Supervisor({"a": child, "b": child})
        sup.start()
        pids = list(sup.pids().values())
    else:                                   # no prctl: only the watchdog can end them
        env = dict(os.environ, **{PARENT_PID_ENV: str(os.getpid())})
        pids = [subprocess.Popen(child, env=env).pid for _ in range(2)]
    print(" ".join(map(str, pids)), flush=True)
    time.sleep(60)
""")

# A child that ignores SIGTERM: only the watchdog's hard exit ends it after its parent died.
_STUBBORN_CHILD = textwrap.dedent("""
    import signal, time
    from backlash_monitor.process.parent_watch import start_watchdog
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    assert start_watchdog(grace_s=1.0, period_s=0.1) is not None
    time.sleep(60)
""")


# A child whose main thread blocks in C while it holds the GIL (libc's sleep through ctypes.PyDLL,
# which keeps the GIL), and ignores SIGTERM: the watchdog's thread can never run again, so only a
# stage outside the process's interpreter ends it. Before that stage, this child outlived its
# parent for good (a killed pipeline's node, once in CI).
_GIL_HOLDING_CHILD = textwrap.dedent("""
    import ctypes, signal
    from backlash_monitor.process.parent_watch import start_watchdog
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    assert start_watchdog(grace_s=1.0, period_s=0.1) is not None
    ctypes.PyDLL(None).sleep(120)
""")


@pytest.mark.process
@pytest.mark.parametrize("how, child", [
    ("supervisor", "import time; time.sleep(60)"),
    ("watchdog", _STUBBORN_CHILD),
    ("watchdog", _GIL_HOLDING_CHILD),
], ids=["supervisor", "watchdog", "watchdog-gil-held"])
def test_children_die_when_their_parent_is_killed_with_sigkill(how, child):
    parent = subprocess.Popen([sys.executable, "-c", _PARENT, how, child], stdout=subprocess.PIPE,
                              text=True, start_new_session=True)
    try:
        pids = [int(p) for p in parent.stdout.readline().split()]
        assert len(pids) == 2
        time.sleep(0.5)       # the children have started (and the watchdogs run)
        assert not any(gone(p) for p in pids)
        parent.kill()
        parent.wait()
        assert wait_until(lambda: all(gone(p) for p in pids), timeout_s=30.0), pids   # a loaded machine
    finally:
        try:
            os.killpg(parent.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        parent.communicate()


@pytest.mark.process
def test_the_watchdog_ignores_a_variable_that_names_another_process():
    code = ("import os; from backlash_monitor.process.parent_watch import start_watchdog, PARENT_PID_ENV; "
            "print(start_watchdog() is None, PARENT_PID_ENV in os.environ)")
    env = dict(os.environ, **{PARENT_PID_ENV: "1"})
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=30)
    assert out.stdout.split() == ["True", "False"], out.stderr


@pytest.mark.process
def test_the_stream_waits_for_the_named_reader_not_for_a_count():
    signals = ("a1", "a2", "omega1", "omega2", "angle_difference")
    wanted = parse_wanted(["windowing:a1,a2,angle_difference", "/rec"], "/line1", signals)
    assert [w.node for w in wanted] == ["/line1/windowing", "/rec"]
    assert wanted[1].signals == signals
    recorder_only = {s: TopicState(frozenset({"/rec"}), 1, 1) for s in signals}
    # Before: three matched subscriptions (here five, all the recorder's) started the stream.
    assert missing(wanted, recorder_only) == ["/line1/windowing on a1, a2, angle_difference"]
    both = {s: TopicState(frozenset({"/rec", "/line1/windowing"}), 2, 2) for s in signals}
    assert missing(wanted, both) == []
    discovered_not_matched = dict(both, a2=TopicState(frozenset({"/rec", "/line1/windowing"}), 2, 1))
    assert missing(wanted, discovered_not_matched) == ["a2: 1 of 2 subscriptions matched"]
    with pytest.raises(ValueError, match="unknown signal a3"):
        parse_wanted(["windowing:a1,a3"], "/", signals)
    with pytest.raises(ValueError, match="names no node"):
        parse_wanted([":a1"], "/", signals)
