"""record / replay nodes through real DDS (loopback, a domain per test): signals close the file
properly, a SIGKILL loses at most the open chunk, replay reproduces the recording."""
from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("rclpy")
pytest.importorskip("backlash_monitor_msgs.msg")

from backlash_monitor.bag import BagReader, TruncatedBagError  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from bag_helpers import write_sample_bag  # noqa: E402


def _start_recorder(env, out, *params):
    args = [sys.executable, "-m", "backlash_monitor.nodes.record", "--ros-args",
            "-p", f"output:={out}", "-p", "discovery_period_s:=0.05", *sum((["-p", p] for p in params), [])]
    return subprocess.Popen(args, env=env, cwd=REPO, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)


def _publish(env, seconds, factor, wait=True):
    args = [sys.executable, str(REPO / "bench" / "bags.py"), "--role", "publish",
            "--seconds", str(seconds), "--factor", str(factor)]
    if not wait:
        return subprocess.Popen(args, env=env, cwd=REPO, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
    proc = subprocess.run(args, env=env, cwd=REPO, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _stop(proc, sig=signal.SIGINT, timeout=20):
    if proc.poll() is None:
        proc.send_signal(sig)
    try:
        out, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
        pytest.fail(f"process did not stop on {sig!r}:\n{out}")
    return proc.returncode, out


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signal_closes_the_bag_properly(ros_env, tmp_path, sig):
    out = tmp_path / "rec.mcap"
    rec = _start_recorder(ros_env, out, "topics:=plant/*", "chunk_duration_s:=0.2")
    try:
        result = _publish(ros_env, 1.0, 2.0)
        time.sleep(0.3)
    finally:
        rc, log = _stop(rec, sig)
    assert rc == 0, log
    assert "Traceback" not in log
    assert result["matched"]
    with BagReader(out) as bag:  # strict: footer, summary, statistics present
        assert bag.recovery.complete
        assert {t: i.count for t, i in bag.topics.items()} == result["published"]
        info = bag.topics["/plant/a1"]
        assert "reliability: reliable" in info.offered_qos_profiles
        assert info.type_hash.startswith("RIHS01_")
        series = bag.read_signals()
        assert all(s.gaps == [] and s.samples.size == 100 * 1000 for s in series.values())
    from mcap.reader import make_reader

    with open(out, "rb") as f:
        summary = make_reader(f).get_summary()
    assert summary.statistics.message_count == sum(result["published"].values())


@pytest.mark.process
@pytest.mark.ros
def test_sigkill_loses_at_most_the_open_chunk(ros_env, tmp_path, capsys):
    out = tmp_path / "killed.mcap"
    chunk_s = 0.25
    rec = _start_recorder(ros_env, out, "topics:=plant/*", f"chunk_duration_s:={chunk_s}")
    pub = _publish(ros_env, 4.0, 1.0, wait=False)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and (not out.exists() or out.stat().st_size < 600_000):
            time.sleep(0.05)
        assert out.exists() and out.stat().st_size >= 600_000, "recorder did not record"
        killed_ns = time.time_ns()
        rec.kill()
        rec.wait(timeout=10)
    finally:
        if rec.poll() is None:
            rec.kill()
        pub.kill()  # the load generator: no need to wait for acks from a dead recorder
        pub.communicate(timeout=30)
    with pytest.raises(TruncatedBagError):
        BagReader(out)
    with BagReader(out, recover=True) as bag:
        rep = bag.recovery
        assert not rep.complete and rep.complete_chunks >= 1
        msgs = list(bag.messages())
        assert msgs and len(msgs) == rep.messages
        last = max(m.log_time_ns for m in msgs)
        # at most one chunk (0.25 s) plus the flush timer's period and scheduling slack is lost
        assert killed_ns - last < (chunk_s * 2 + 0.3) * 1e9, (killed_ns - last) / 1e9
        for series in bag.read_signals().values():
            assert series.gaps == [] and series.sample_index[0] == 0
    cli = [sys.executable, "-m", "backlash_monitor", "bag-info", str(out)]
    strict = subprocess.run(cli, capture_output=True, text=True, cwd=REPO, timeout=60)
    assert strict.returncode == 1 and "incomplete" in strict.stderr and "--recover" in strict.stderr
    assert "Traceback" not in strict.stderr + strict.stdout
    from backlash_monitor.__main__ import main as cli_main

    assert cli_main(["bag-info", str(out), "--recover"]) == 0
    printed = capsys.readouterr().out
    assert "INCOMPLETE" in printed and "recovered" in printed
    # it says how much time the lost open chunk held: the writer's bound, or the cut chunk's range
    assert (f"at most {chunk_s:g} s (its chunk_duration_s)" in printed
            or "the chunk being written when the file ends held log time" in printed), printed
    assert rep.chunk_duration_s == chunk_s and rep.damaged == []


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("layout", [None, {"noSummary": True, "noRepeatedChannels": True}],
                         ids=["project", "rosbag2 noSummary"])
def test_replay_flow_controlled_reproduces_the_bag_and_fresh_stamps_shift(ros_env, tmp_path, layout):
    src = tmp_path / "src.mcap"
    write_sample_bag(src, n_chunks=100)
    if layout:   # the same recording as another writer lays it out (test_bag_layouts.py)
        from mcap_conformance import rewrite_with_mcap
        src = rewrite_with_mcap(src, tmp_path / "other_layout.mcap", **layout)
    out = tmp_path / "replayed.mcap"
    rec = _start_recorder(ros_env, out)
    try:
        play = subprocess.run(
            [sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args", "-p", f"bag:={src}",
             "-p", "rate:=0.0", "-p", "stamps:=fresh", "-p", "wait_timeout_s:=30.0"],
            env=ros_env, cwd=REPO, capture_output=True, text=True, timeout=90)
        assert play.returncode == 0, play.stdout + play.stderr
        time.sleep(0.3)
    finally:
        rc, log = _stop(rec)
    assert rc == 0, log
    with BagReader(src) as a, BagReader(out) as b:
        assert {t: i.count for t, i in a.topics.items()} == {t: i.count for t, i in b.topics.items()}
        for topic in a.topics:
            ma = [m.message for m in a.messages(topic)]
            mb = [m.message for m in b.messages(topic)]
            shift = None
            for x, y in zip(ma, mb):
                dx = x.header.stamp.sec * 10**9 + x.header.stamp.nanosec
                dy = y.header.stamp.sec * 10**9 + y.header.stamp.nanosec
                shift = dy - dx if shift is None else shift
                assert dy - dx == shift  # one constant offset
                x.header.stamp, y.header.stamp = None, None
                assert x == y
            assert shift > 0  # stamps moved to the replay's (later) time


@pytest.mark.process
@pytest.mark.ros
def test_replay_at_recorded_rate_keeps_the_timing(ros_env, tmp_path):
    src = tmp_path / "src.mcap"
    write_sample_bag(src, n_chunks=50)  # 1 s of stream
    out = tmp_path / "timed.mcap"
    rec = _start_recorder(ros_env, out, "topics:=/plant/a1")
    try:
        play = subprocess.run(
            [sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args", "-p", f"bag:={src}",
             "-p", "rate:=2.0", "-p", "topics:=plant/a1", "-p", "wait_for_subscribers:=1",
             "-p", "qos:=reliable"],
            env=ros_env, cwd=REPO, capture_output=True, text=True, timeout=90)
        assert play.returncode == 0, play.stdout + play.stderr
        time.sleep(0.3)
    finally:
        _stop(rec)
    with BagReader(out) as bag:
        assert bag.topics["/plant/a1"].count == 50
        # 49 intervals of 20 ms at 2x: 0.49 s. The recorder stamps on arrival, and on a loaded machine the first
        # chunks can arrive late together (measured 0.393 s with the whole suite and four other jobs on 2 cores);
        # a replay ignoring the rate would take a few ms
        assert 0.30e9 < bag.duration_ns < 0.75e9, bag.duration_ns / 1e9


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("node, params, named", [
    ("record", ["compression:=gzip"], "compression"),
    ("record", ["chunk_duration_s:=0.0"], "chunk_duration_s"),
    ("record", ["exclude_regex:=(("], "exclude_regex"),
    ("replay", ["bag:=/nonexistent/run.mcap"], "bag"),
    ("replay", ["bag:=x.mcap", "rate:=-1.0"], "rate"),
    ("replay", ["bag:=x.mcap", "stamps:=now"], "stamps"),
])
def test_nodes_reject_bad_parameters_clearly(ros_env, tmp_path, node, params, named):
    proc = subprocess.run([sys.executable, "-m", f"backlash_monitor.nodes.{node}", "--ros-args",
                           *sum((["-p", p] for p in params), [])],
                          env=ros_env, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert f"parameter '{named}'" in proc.stderr and "allowed" in proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout


_ASK_RATE = """
import rclpy
from rclpy.parameter_client import AsyncParameterClient
rclpy.init()
node = rclpy.create_node("asker")
client = AsyncParameterClient(node, "replay")
assert client.wait_for_services(timeout_sec=30.0)
future = client.get_parameters(["rate"])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print(future.result().values[0].double_value if future.done() else "no answer")
"""


@pytest.mark.process
@pytest.mark.ros
def test_replay_answers_its_parameter_services_while_it_plays(ros_env, tmp_path):
    src = tmp_path / "src.mcap"
    write_sample_bag(src, n_chunks=250)  # 5 s of stream, played at the recorded rate
    play = subprocess.Popen(
        [sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args", "-p", f"bag:={src}",
         "-p", "rate:=1.0", "-p", "topics:=plant/a1"],
        env=ros_env, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        ask = subprocess.run([sys.executable, "-c", _ASK_RATE], env=ros_env, capture_output=True,
                             text=True, timeout=60)
        still_playing = play.poll() is None
    finally:
        code, out = _stop(play)
    assert ask.returncode == 0, ask.stderr
    assert ask.stdout.strip() == "1.0"
    assert still_playing             # the answer came during the 5 s of playing
    assert "Traceback" not in out


@pytest.mark.process
@pytest.mark.ros
def test_sigkill_loses_only_what_a_second_recorder_got_in_the_last_open_chunk(ros_env, tmp_path):
    """Two recorders take the same stream; one is killed. Every message the other one received
    before the kill is in the killed one's recovered bag, except those of the last chunk_duration_s
    (its open chunk) plus delivery slack: the loss measured against a reference, not a clock."""
    chunk_s = 0.25
    killed_bag, reference_bag = tmp_path / "killed.mcap", tmp_path / "reference.mcap"
    victim = _start_recorder(ros_env, killed_bag, "topics:=plant/*", f"chunk_duration_s:={chunk_s}")
    reference = _start_recorder(ros_env, reference_bag, "topics:=plant/*",
                                f"chunk_duration_s:={chunk_s}")
    time.sleep(1.0)
    pub = _publish(ros_env, 4.0, 1.0, wait=False)
    try:
        deadline = time.monotonic() + 60    # the stream flows: both recorders closed chunks
        while time.monotonic() < deadline and not all(
                b.exists() and b.stat().st_size >= 150_000 for b in (reference_bag, killed_bag)):
            time.sleep(0.05)                # (a recorder slow to start on a loaded machine)
        time.sleep(1.0)
        killed_ns = time.time_ns()
        victim.kill()
        victim.wait(timeout=10)
        time.sleep(0.5)                     # the reference takes what was on its way
    finally:
        for proc in (victim, pub):          # (a publisher would wait for a dead reader's acks)
            if proc.poll() is None:
                proc.kill()
            proc.communicate(timeout=30)
        rc, log = _stop(reference)
    assert rc == 0, log

    def keys(bag):
        return {(m.topic, m.message.first_sample_index): m.log_time_ns for m in bag.messages()}

    with BagReader(reference_bag) as bag:
        ref = keys(bag)
    with BagReader(killed_bag, recover=True) as bag:
        got = keys(bag)
    # compared where both recorders were subscribed: each topic from the later of their first
    # messages (each recorder subscribes on its own discovery; either may start later)
    def first_index(keys_):
        first = {}
        for topic, index in keys_:
            first[topic] = min(first.get(topic, index), index)
        return first

    first_got, first_ref = first_index(got), first_index(ref)
    start = {topic: max(i, first_ref[topic]) for topic, i in first_got.items() if topic in first_ref}
    before = {k: t for k, t in ref.items() if t < killed_ns and k[0] in start and k[1] >= start[k[0]]}
    common = {k for k in got if k[0] in start and k[1] >= start[k[0]]}
    missing = [t for k, t in before.items() if k not in got]
    assert len(before) > 100 and common <= set(ref)
    assert len(missing) < len(before) // 2
    # only the open chunk: a chunk is closed at chunk_duration_s by the next write or by the flush
    # timer (every chunk_duration_s), so it holds at most 2 x chunk_duration_s (+ 0.1 s delivery)
    assert all(killed_ns - t <= (2 * chunk_s + 0.1) * 1e9 for t in missing), \
        sorted((killed_ns - t) / 1e9 for t in missing)[-5:]
