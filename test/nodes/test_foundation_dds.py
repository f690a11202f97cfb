"""DDS stays on loopback, and two nodes in two processes exchange the project's messages."""
import pytest
import os
import subprocess
import time

from ament_index_python.packages import get_package_prefix


def _executable(name):
    # Resolved as `ros2 run backlash_monitor <name>` does.
    return os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", name)


@pytest.mark.process
@pytest.mark.ros
def test_each_test_gets_a_domain_that_its_processes_do_not_leave(ros_env):
    """Two ros_env domains are really apart: a talker waiting for a listener in another domain
    never finds it (in one domain they do: test_two_processes_exchange_signal_chunks)."""
    from conftest import fresh_domain_id

    other = dict(ros_env, ROS_DOMAIN_ID=str(fresh_domain_id()))
    assert ros_env["ROS_AUTOMATIC_DISCOVERY_RANGE"] == other["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
    listener = subprocess.Popen([_executable("chunk_listener"), "--ros-args", "-p", "count:=1"],
                                env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    talker = subprocess.Popen([_executable("chunk_talker"), "--ros-args", "-p", "count:=1"],
                              env=other, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        time.sleep(4.0)      # discovery on loopback takes well under a second in one domain
        still_waiting = listener.poll() is None and talker.poll() is None
    finally:
        for proc in (listener, talker):
            proc.kill()
        listener_out, _ = listener.communicate(timeout=30)
        talker.communicate(timeout=30)
    assert still_waiting, listener_out
    assert "chunk " not in listener_out


def test_every_make_target_and_env_sh_keep_dds_on_loopback(repo_root):
    makefile = (repo_root / "Makefile").read_text()
    assert "export ROS_AUTOMATIC_DISCOVERY_RANGE := LOCALHOST" in makefile
    assert "export ROS_DOMAIN_ID" in makefile
    env_sh = (repo_root / "env.sh").read_text()
    assert "export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST" in env_sh
    assert "ROS_DOMAIN_ID" in env_sh


@pytest.mark.process
@pytest.mark.ros
def test_two_processes_exchange_signal_chunks(ros_env):
    listener = subprocess.Popen(
        [_executable("chunk_listener"), "--ros-args", "-p", "count:=5"],
        env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    talker = subprocess.Popen(
        [_executable("chunk_talker"), "--ros-args", "-p", "count:=5", "-p", "chunk_samples:=1000"],
        env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        listener_out, _ = listener.communicate(timeout=60)
        talker_out, _ = talker.communicate(timeout=30)
    finally:
        for proc in (listener, talker):
            if proc.poll() is None:
                proc.kill()
    assert listener.returncode == 0, listener_out
    assert talker.returncode == 0, talker_out
    lines = [line for line in listener_out.splitlines() if line.startswith("chunk ")]
    assert len(lines) == 5
    assert all(line.endswith("continuous") and "samples=1000" in line for line in lines)
    assert "first_sample_index=4000" in lines[-1]
