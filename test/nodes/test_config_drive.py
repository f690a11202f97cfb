"""config/drive.yaml: every key is a parameter the node declares, every value one it allows, and
the chain starts with the file and takes its values (a drive's settings in one place)."""
import pytest
import os
import subprocess
import sys
import textwrap

import yaml
from ament_index_python.packages import get_package_prefix, get_package_share_directory

from backlash_monitor.nodes.classifier import PARAMETERS as CLASSIFIER
from backlash_monitor.nodes.denoise import PARAMETERS as DENOISE
from backlash_monitor.nodes.windowing import PARAMETERS as WINDOWING

NODES = {"windowing": WINDOWING, "denoise": DENOISE, "classifier": CLASSIFIER}


def _file(repo_root):
    return yaml.safe_load((repo_root / "config" / "drive.yaml").read_text())


@pytest.mark.ros
def test_every_key_is_declared_and_every_value_allowed(repo_root):
    sections = _file(repo_root)
    shared = sections["/**"]["ros__parameters"]
    for node, specs in NODES.items():
        by_name = {spec.name: spec for spec in specs}
        own = sections[f"/**/{node}"]["ros__parameters"]
        for key, value in own.items():
            assert key in by_name, f"{node}: {key} is not a parameter of the node"
            assert by_name[key].check(value) == value
        for key, value in shared.items():   # a shared key must mean something to some node
            if key in by_name:
                assert by_name[key].check(value) == value
    assert all(any(key in {s.name for s in specs} for specs in NODES.values()) for key in shared)


@pytest.mark.ros
def test_the_file_is_installed_with_the_package(repo_root):
    installed = os.path.join(get_package_share_directory("backlash_monitor"), "config", "drive.yaml")
    assert open(installed).read() == (repo_root / "config" / "drive.yaml").read_text()


_READ_BACK = textwrap.dedent("""
    import rclpy
    from rclpy.parameter_client import AsyncParameterClient
    rclpy.init()
    node = rclpy.create_node("reader")
    out = []
    for target, names in (("/line1/drive7/windowing", ["drive_name", "qos", "trigger"]),
                          ("/line1/drive7/classifier", ["drive_name", "n1", "warn_width_m"])):
        client = AsyncParameterClient(node, target)
        assert client.wait_for_services(timeout_sec=60.0), target
        future = client.get_parameters(names)
        rclpy.spin_until_future_complete(node, future, timeout_sec=30.0)
        for name, value in zip(names, future.result().values):
            out.append(f"{target} {name} " + str(value.string_value or value.double_value))
    print("\\n".join(out))
""")


@pytest.mark.process
@pytest.mark.ros
def test_the_chain_starts_with_the_file_and_takes_its_values(ros_env):
    prefix = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")
    path = os.path.join(get_package_share_directory("backlash_monitor"), "config", "drive.yaml")
    chain = subprocess.Popen([os.path.join(prefix, "chain"), "--ros-args", "-r", "__ns:=/line1/drive7",
                              "--params-file", path, "-p", "drive_name:=drive7"],
                             env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        out = subprocess.run([sys.executable, "-c", _READ_BACK], env=ros_env, capture_output=True,
                             text=True, timeout=120)
    finally:
        chain.terminate()
        chain_out, _ = chain.communicate(timeout=30)
    assert out.returncode == 0, out.stderr + chain_out
    values = dict(line.rsplit(" ", 1) for line in out.stdout.splitlines())
    assert values == {
        "/line1/drive7/windowing drive_name": "drive7",      # -p after the file wins
        "/line1/drive7/windowing qos": "sensor_data",
        "/line1/drive7/windowing trigger": "contact_loss",
        "/line1/drive7/classifier drive_name": "drive7",
        "/line1/drive7/classifier n1": "0.89",
        "/line1/drive7/classifier warn_width_m": "0.0075",
    }, out.stdout
    assert "Traceback" not in chain_out
