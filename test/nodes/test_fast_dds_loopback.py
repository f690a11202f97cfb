"""On a graph kept to this machine (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST) the project's processes talk over
loopback UDP, not through Fast DDS's shared-memory ports (ros/fast_dds.py; docs/graph.md "Loopback UDP, not shared
memory"): a shared-memory port is judged dead when its listener stops for 1 s, and a hop's data twice stopped for good
after a process of the graph was stopped or killed."""
import os
import subprocess
import time

import pytest

from backlash_monitor.ros import fast_dds


def test_localhost_gets_the_loopback_udp_locator_and_other_ranges_do_not():
    for value in ("LOCALHOST", "localhost", " LOCALHOST "):
        profile = fast_dds.profile_for_range(value)
        assert "<udpv4><address>127.0.0.1</address></udpv4>" in profile and "heartbeatPeriod" in profile
    for value in (None, "", "SUBNET", "SYSTEM_DEFAULT", "OFF"):
        profile = fast_dds.profile_for_range(value)
        assert "defaultUnicastLocatorList" not in profile and "heartbeatPeriod" in profile


def test_a_childs_environment_points_at_its_ranges_profile_and_a_users_file_is_left_alone(tmp_path):
    env = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
    fast_dds.profile_env(env)
    assert open(env["FASTRTPS_DEFAULT_PROFILES_FILE"]).read() == fast_dds.LOOPBACK_FAST_DDS_PROFILE
    env = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}
    fast_dds.profile_env(env)
    assert open(env["FASTRTPS_DEFAULT_PROFILES_FILE"]).read() == fast_dds.FAST_DDS_PROFILE
    mine = tmp_path / "mine.xml"
    for key in ("FASTRTPS_DEFAULT_PROFILES_FILE", "FASTDDS_DEFAULT_PROFILES_FILE"):
        env = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", key: str(mine)}
        fast_dds.profile_env(env)
        assert env == {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", key: str(mine)}


def _shm_ports(pid: int) -> set:
    with open(f"/proc/{pid}/maps") as f:
        return {line.split()[-1] for line in f if "fastrtps_port" in line}


@pytest.mark.ros
def test_a_localhost_graph_streams_with_no_shared_memory_port(ros_env):
    """A plant and the chain (windowing, denoise, classifier in one process) on LOCALHOST: the stream's windows are
    made and classified, and neither process maps a Fast DDS shared-memory port."""
    from ament_index_python.packages import get_package_prefix
    prefix = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")
    chain = subprocess.Popen([os.path.join(prefix, "chain"), "--ros-args", "-p", "qos:=reliable"], env=ros_env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    plant = subprocess.Popen([os.path.join(prefix, "plant_simulator"), "--ros-args", "-p", "qos:=reliable",
                              "-p", "duration_s:=3.0", "-p", "rate_factor:=1.0",
                              "-p", "wait_for_subscribers:=['windowing:a1,a2,angle_difference']"],
                             env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(2.0)
        ports = {"chain": _shm_ports(chain.pid), "plant": _shm_ports(plant.pid)}
        _, plant_err = plant.communicate(timeout=120)
    finally:
        for proc in (plant, chain):
            if proc.poll() is None:
                proc.terminate()
        chain_out, _ = chain.communicate(timeout=60)
    assert "streaming" in plant_err and "published 150 chunks" in plant_err, plant_err
    assert "windows/denoised: first message" in chain_out, chain_out + plant_err
    assert ports == {"chain": set(), "plant": set()}, ports
