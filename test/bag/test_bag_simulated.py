"""`simulate --mcap` writes bags in batch mode (no DDS) with the live graph's topic layout."""
import pytest
import subprocess
import sys

import numpy as np
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore, get_types_from_msg

from backlash_monitor.bag import BagReader


@pytest.mark.process
def test_simulated_bags_hold_the_npz_samples_in_the_live_layout(tmp_path, repo_root):
    npz = tmp_path / "sim.npz"
    bags = tmp_path / "bags"
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "simulate", "--widths", "0.005",
                           "--eta-k", "0.025", "--n1", "0.89", "--duration", "0.5", "-o", str(npz),
                           "--mcap", str(bags), "--no-progress"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    data = np.load(npz)
    (bag,) = sorted(bags.glob("*.mcap"))
    assert bag.name == "w5mm_eta0.025_n0.89_s0.mcap"
    with BagReader(bag) as reader:
        assert set(reader.topics) == {"/plant/a1", "/plant/a2", "/plant/omega1", "/plant/omega2",
                                      "/plant/angle_difference", "/plant/true_width_m"}
        series = reader.read_signals()
        (width_msg,) = [m.message for m in reader.messages(["/plant/true_width_m"])]
    assert width_msg.data == 0.005
    for name in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        s = series[f"/plant/{name}"]
        assert not s.gaps
        assert np.array_equal(s.samples, data[name][0])
        assert np.array_equal(s.chunk_first_index, np.arange(0, 25000, 1000))

    # An independent reader decodes it with the schema text stored in the file.
    typestore = get_typestore(Stores.ROS2_JAZZY)
    typestore.register(get_types_from_msg(
        (repo_root / "msg_defs/msg/SignalChunk.msg").read_text(),
        "backlash_monitor_msgs/msg/SignalChunk"))
    with AnyReader([bag], default_typestore=typestore) as reader:
        conns = [c for c in reader.connections if c.topic == "/plant/a1"]
        first = next(reader.messages(connections=conns))
        msg = reader.deserialize(first[2], conns[0].msgtype)
    assert msg.first_sample_index == 0 and np.array_equal(msg.samples, data["a1"][0, :1000])
