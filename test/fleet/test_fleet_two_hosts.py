"""Two hosts: the plant in one network namespace, the chain in another, joined by a veth pair;
DDS configured for exactly those two addresses (unicast discovery, no multicast, no shared
memory). The estimates must come back to the plant's host for every onset window."""
import subprocess

import pytest

from backlash_monitor.ros.netns import can_make_namespaces, run_two_hosts
from conftest import fresh_domain_id


@pytest.mark.process
@pytest.mark.ros
def test_estimates_cross_between_two_network_namespaces(tmp_path, ros_env):
    reason = can_make_namespaces()
    if reason:
        print(f"skipped: {reason}")
        pytest.skip(reason)
    before = set(subprocess.run(["ip", "netns", "list"], capture_output=True,
                                text=True).stdout.split())
    result = run_two_hosts(str(tmp_path), ros_env, fresh_domain_id(), duration_s=4.0,
                           rate_factor=1.0)
    after = set(subprocess.run(["ip", "netns", "list"], capture_output=True,
                               text=True).stdout.split())
    assert not {n for n in after - before if n.startswith("bm")}, "namespaces left behind"
    logs = "\n".join(f"--- {k}\n{v}" for k, v in result["logs"].items())
    # 4 s of stream: 200 chunks crossed to B, 16 onsets (one every 0.25 s), all but the first (no
    # sensor offset estimate before one whole load period) back in A as estimates
    assert result["chunks"] == 200, logs
    assert result["onset_windows"] == 16 and result["onsets_before_offset"] == 1, logs
    assert result["onsets_estimated"] == 15 and result["delivered"] == 1.0, logs
    assert result["discarded"] == 0
    # ... and the stream went over the veth pair: 200 chunks x 3 topics x 8000 bytes of samples
    assert result["veth_bytes"] > 200 * 3 * 8000, result["veth_bytes"]


@pytest.mark.ros
def test_the_profiles_name_only_the_two_addresses():
    from backlash_monitor.ros.netns import fast_dds_profile
    xml = fast_dds_profile("10.231.5.1", "10.231.5.2")
    import re
    assert set(re.findall(r"<address>([^<]+)</address>", xml)) == {"10.231.5.1", "10.231.5.2"}
    assert "<useBuiltinTransports>false</useBuiltinTransports>" in xml   # no SHM, no default UDP
    assert "Multicast" not in xml
