"""A recorder that stalls (SIGSTOP 2 s, then SIGCONT) loses nothing (issue 34, docs/graph.md "While a
consumer is away"): its reliable queues (queue_depth 1000 per topic, 20 s of a 50 Hz chunk topic)
hold what comes meanwhile, and the bag ends with every message the publisher sent, without a gap."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

pytest.importorskip("rclpy")
pytest.importorskip("backlash_monitor_msgs.msg")

from backlash_monitor.bag import BagReader  # noqa: E402
from test_bag_record_replay import REPO, _start_recorder, _stop  # noqa: E402

from backlash_monitor.ros.qos import RELIABLE_CHUNK_DEPTH  # noqa: E402


@pytest.mark.process
@pytest.mark.ros
def test_a_stalled_recorder_loses_no_message(ros_env, tmp_path):
    out = tmp_path / "stalled.mcap"
    rec = _start_recorder(ros_env, out, "topics:=plant/*", "chunk_duration_s:=0.2")
    # the plant's reliable history (1000 chunks per topic): a writer of 100 (bench/bags.py's
    # default) replaces the chunks the stalled reader has not acknowledged after 2 s at 50 Hz
    pub = subprocess.Popen([sys.executable, str(REPO / "bench" / "bags.py"), "--role", "publish",
                            "--seconds", "4.0", "--factor", "1.0", "--depth", str(RELIABLE_CHUNK_DEPTH)],
                           env=ros_env, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and (not out.exists() or out.stat().st_size < 200_000):
            time.sleep(0.05)
        assert out.exists() and out.stat().st_size >= 200_000, "recorder did not record"
        os.kill(rec.pid, signal.SIGSTOP)
        try:
            time.sleep(2.0)
        finally:
            os.kill(rec.pid, signal.SIGCONT)
        stdout, stderr = pub.communicate(timeout=300)
        assert pub.returncode == 0, stderr[-3000:]
        result = json.loads(stdout.strip().splitlines()[-1])
        time.sleep(2.0)      # the recorder writes its backlog
    finally:
        if pub.poll() is None:
            pub.kill()
            pub.communicate()
        rc, log = _stop(rec, timeout=120)
    assert rc == 0, log
    with BagReader(out) as bag:
        assert {t: i.count for t, i in bag.topics.items()} == result["published"], log
        assert all(s.gaps == [] for s in bag.read_signals().values())


@pytest.mark.process
@pytest.mark.ros
def test_replay_names_the_topics_a_stalled_subscriber_has_not_acknowledged(ros_env, tmp_path):
    """A replay ending while its subscriber is stopped (SIGSTOP) waits wait_timeout_s for the acknowledgements,
    then says which topics' end that subscriber loses, and exits normally (ros/delivery.py)."""
    from bag_helpers import write_sample_bag
    from test_bag_record_replay import _start_recorder, _stop
    src = tmp_path / "src.mcap"
    write_sample_bag(src, n_chunks=250)          # 5 s at the recorded rate
    rec = _start_recorder(ros_env, tmp_path / "out.mcap")
    play = subprocess.Popen(
        [sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args", "-p", f"bag:={src}", "-p", "rate:=1.0",
         "-p", "qos:=reliable", "-p", "wait_for_subscribers:=1", "-p", "wait_timeout_s:=3.0"],
        env=ros_env, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    stopped = False
    try:
        seen = set()
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and not any(t.startswith("/plant/") for t in seen):
            line = rec.stdout.readline()
            if not line:
                break
            if "recording /" in line:
                seen.add(line.split("recording ", 1)[1].split()[0])
        assert seen, "the recorder subscribed to nothing"
        time.sleep(1.0)                          # replay plays (it waited for the subscription)
        os.kill(rec.pid, signal.SIGSTOP)
        stopped = True
        out, _ = play.communicate(timeout=120)
    finally:
        if play.poll() is None:
            play.kill()
            play.communicate()
        if stopped:
            os.kill(rec.pid, signal.SIGCONT)
        _stop(rec, timeout=60)
    assert play.returncode == 0, out
    assert "not acknowledged after 3 s on" in out and "/plant/" in out.split("not acknowledged", 1)[1], out
