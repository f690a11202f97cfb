"""The package is laid out exactly as a ROS 2 Jazzy install expects it.

`ros2 run backlash_monitor <exe>` resolves an executable as ros2run does: the package prefix from
the ament index (ament_index_python.get_package_prefix), then <prefix>/lib/backlash_monitor/<exe>.
These tests do the same lookups against the colcon install that `make setup` built.
"""
import pytest
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from ament_index_python.packages import get_package_prefix, get_package_share_directory


def _executables_from_setup(repo_root):
    namespace = {}
    source = (repo_root / "setup.py").read_text()
    start = source.index("EXECUTABLES = {")
    end = source.index("}", start) + 1
    exec(source[start:end], namespace)
    return namespace["EXECUTABLES"]


@pytest.mark.ros
def test_package_xml_is_format_3_ament_python_with_real_dependencies(repo_root):
    root = ET.parse(repo_root / "package.xml").getroot()
    assert root.get("format") == "3"
    assert root.findtext("name") == "backlash_monitor"
    assert root.find("export/build_type").text == "ament_python"
    deps = {e.text for e in root if e.tag.endswith("depend")}
    for dep in ("rclpy", "std_msgs", "diagnostic_msgs", "backlash_monitor_msgs",
                "python3-numpy", "python3-scipy", "python3-pywt"):
        assert dep in deps, dep


def test_interface_package_is_rosidl(repo_root):
    root = ET.parse(repo_root / "msg_defs" / "package.xml").getroot()
    assert root.findtext("name") == "backlash_monitor_msgs"
    assert root.findtext("member_of_group") == "rosidl_interface_packages"
    assert root.find("export/build_type").text == "ament_cmake"
    cmake = (repo_root / "msg_defs" / "CMakeLists.txt").read_text()
    for msg in sorted((repo_root / "msg_defs" / "msg").glob("*.msg")):
        assert f'"msg/{msg.name}"' in cmake, msg.name


def test_ament_index_knows_both_packages():
    prefix = get_package_prefix("backlash_monitor")
    assert os.path.isfile(os.path.join(prefix, "share", "ament_index", "resource_index",
                                       "packages", "backlash_monitor"))
    share = get_package_share_directory("backlash_monitor")
    assert os.path.isfile(os.path.join(share, "package.xml"))
    get_package_prefix("backlash_monitor_msgs")


def test_every_executable_resolves_as_ros2_run_does(repo_root):
    prefix = get_package_prefix("backlash_monitor")
    for name in _executables_from_setup(repo_root):
        path = os.path.join(prefix, "lib", "backlash_monitor", name)
        assert os.path.isfile(path) and os.access(path, os.X_OK), path


@pytest.mark.ros
def test_generated_messages_import_and_round_trip():
    from rclpy.serialization import deserialize_message, serialize_message

    from backlash_monitor_msgs.msg import BacklashEstimate, BacklashWindow, SignalChunk

    chunk = SignalChunk(signal_name="a1", unit="m/s^2", sample_period_s=2e-5,
                        first_sample_index=4096, samples=[0.5, -1.25, 3.0])
    back = deserialize_message(serialize_message(chunk), SignalChunk)
    assert back.first_sample_index == 4096 and list(back.samples) == [0.5, -1.25, 3.0]
    assert hasattr(BacklashWindow(), "entry_kind")
    assert hasattr(BacklashEstimate(), "b_vector")


@pytest.mark.process
def test_colcon_finds_both_packages_with_the_documented_base_paths(repo_root):
    out = subprocess.run([sys.executable, "-m", "colcon", "list", "--base-paths", ".", "msg_defs",
                          "--topological-order", "--names-only"],
                         cwd=repo_root, capture_output=True, text=True, check=True).stdout.split()
    # The interface package must be built before the package that runs with it.
    assert out == ["backlash_monitor_msgs", "backlash_monitor"]
