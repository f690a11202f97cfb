"""A finite stream's end reaches a subscriber that is behind (issue "under load and with real sensors": no upstream
loss): the plant simulator, once its duration is published, waits for every reliable subscriber to acknowledge every
chunk before it exits (finish_timeout_s). A reliable chunk still in a publisher's history is lost with its process:
across two hosts the chain once got 199 of 200 chunks, and a chain stalled beside a CPU hog lost every onset after the
stall (a chunk of the stream's end never came, and the joiner waits for it)."""
import os
import signal
import subprocess
import sys
import time

import pytest

_COUNTER = """
import sys, time, rclpy
from backlash_monitor.ros.qos import chunk_qos
from backlash_monitor_msgs.msg import SignalChunk
rclpy.init()
node = rclpy.create_node("counter")
got = []
node.create_subscription(SignalChunk, "plant/a1", lambda m: got.append(m.first_sample_index), chunk_qos("reliable"))
print("subscribed", flush=True)
deadline = time.monotonic() + float(sys.argv[2])
while len(got) < int(sys.argv[1]) and time.monotonic() < deadline:
    rclpy.spin_once(node, timeout_sec=0.1)
print(len(got), len(set(got)), flush=True)
"""
CHUNKS = 50                  # 1 s at 1000 samples a chunk


def _plant(ros_env, *params):
    from ament_index_python.packages import get_package_prefix
    exe = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", "plant_simulator")
    args = [exe, "--ros-args", "-p", "qos:=reliable", "-p", "duration_s:=1.0", "-p", "rate_factor:=1.0",
            "-p", "wait_for_subscriptions:=1"]
    for p in params:
        args += ["-p", p]
    return subprocess.Popen(args, env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@pytest.mark.process
@pytest.mark.ros
def test_the_plant_waits_for_a_stalled_subscriber_to_take_the_streams_end(ros_env):
    counter = subprocess.Popen([sys.executable, "-c", _COUNTER, str(CHUNKS), "120"], env=ros_env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert counter.stdout.readline().strip() == "subscribed"
    plant = _plant(ros_env, "finish_timeout_s:=60.0")
    try:
        lines = []
        for line in plant.stderr:
            lines.append(line)
            if "streaming" in line:
                break
        # the subscriber stops taking messages as the stream begins (1 s in real time) and ends
        os.kill(counter.pid, signal.SIGSTOP)
        try:
            for line in plant.stderr:
                lines.append(line)
                if "published" in line:
                    break
            assert any(f"published {CHUNKS} chunks" in line for line in lines), "".join(lines)
            time.sleep(2.0)
            # all published, the subscriber still stopped: the plant is still there, holding what it has not taken
            assert plant.poll() is None, "".join(lines)
        finally:
            os.kill(counter.pid, signal.SIGCONT)
        out, err = counter.communicate(timeout=120)
        assert out.split() == [str(CHUNKS), str(CHUNKS)], out + err + "".join(lines)
        # ... and once it has taken them, the plant ends at once, with no warning
        rest = plant.communicate(timeout=30)[1]
        assert plant.returncode == 0 and "not acknowledged" not in rest, rest
    finally:
        for proc in (plant, counter):
            if proc.poll() is None:
                os.kill(proc.pid, signal.SIGCONT)
                proc.terminate()
                proc.communicate(timeout=30)


@pytest.mark.process
@pytest.mark.ros
def test_a_subscriber_that_never_takes_the_end_is_named_and_the_plant_still_exits(ros_env):
    counter = subprocess.Popen([sys.executable, "-c", _COUNTER, str(CHUNKS), "120"], env=ros_env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert counter.stdout.readline().strip() == "subscribed"
    plant = _plant(ros_env, "finish_timeout_s:=1.0")
    try:
        for line in plant.stderr:
            if "streaming" in line:
                break
        os.kill(counter.pid, signal.SIGSTOP)
        err = plant.communicate(timeout=60)[1]
        assert plant.returncode == 0, err
        assert "not acknowledged after 1 s on plant/a1" in err and "finish_timeout_s" in err, err
    finally:
        os.kill(counter.pid, signal.SIGCONT)
        counter.terminate()
        counter.communicate(timeout=30)
        if plant.poll() is None:
            plant.terminate()
            plant.communicate(timeout=30)
