"""Two "hosts" on one machine: two network namespaces joined by a veth pair, DDS between them only.

For the several-machines test and bench (docs/fleet.md): host A runs a drive's plant simulator and
a monitor, host B the drive's chain; the chunks cross the veth pair to B and the estimates cross
back to A. Each namespace has only its loopback and its end of the pair (no route anywhere else),
and each process gets a Fast DDS profile (:func:`fast_dds_profile`) that

- uses UDPv4 on its own address only (no shared-memory transport, which would bypass the
  network: /dev/shm is shared between network namespaces),
- discovers by unicast to the other host's address (initial peers) and listens for discovery
  on its own address only, so no multicast is sent anywhere,
- keeps the project's 10 ms writer heartbeat (ros/fast_dds.py).

Needs root (``ip netns add``); :func:`can_make_namespaces` says why not where it cannot.
"""
from __future__ import annotations

import os
import subprocess
import uuid
from contextlib import contextmanager
from dataclasses import dataclass
import json
import time
import sys

from ament_index_python.packages import get_package_prefix

from backlash_monitor.ros.fast_dds import HEADER_XML, WRITER_PROFILE_XML

SUBNET = "10.231.{n}.{host}"


def fast_dds_profile(own_address: str, peer_address: str) -> str:
    return HEADER_XML + f"""  <transport_descriptors>
    <transport_descriptor>
      <transport_id>veth_udp</transport_id>
      <type>UDPv4</type>
      <interfaceWhiteList><address>{own_address}</address></interfaceWhiteList>
    </transport_descriptor>
  </transport_descriptors>
  <participant profile_name="backlash_monitor_two_hosts" is_default_profile="true">
    <rtps>
      <userTransports><transport_id>veth_udp</transport_id></userTransports>
      <useBuiltinTransports>false</useBuiltinTransports>
      <builtin>
        <initialPeersList>
          <locator><udpv4><address>{peer_address}</address></udpv4></locator>
        </initialPeersList>
        <metatrafficUnicastLocatorList>
          <locator><udpv4><address>{own_address}</address></udpv4></locator>
        </metatrafficUnicastLocatorList>
      </builtin>
      <defaultUnicastLocatorList>
        <locator><udpv4><address>{own_address}</address></udpv4></locator>
      </defaultUnicastLocatorList>
    </rtps>
  </participant>
""" + WRITER_PROFILE_XML + """</profiles>
"""


def can_make_namespaces() -> str:
    """'' if network namespaces can be made here, else the reason."""
    if os.geteuid() != 0:
        return "network namespaces need root (ip netns add)"
    name = f"bmprobe{uuid.uuid4().hex[:6]}"
    try:
        probe = subprocess.run(["ip", "netns", "add", name], capture_output=True, text=True)
    except FileNotFoundError:
        return "the 'ip' command (iproute2) is not installed"
    if probe.returncode != 0:
        return f"ip netns add failed: {probe.stderr.strip()}"
    subprocess.run(["ip", "netns", "del", name], capture_output=True)
    return ""


@dataclass
class Host:
    netns: str
    address: str
    profile_path: str
    veth: str = ""

    def veth_bytes(self) -> int:
        """Bytes sent plus received on this host's end of the pair so far."""
        out = subprocess.run(["ip", "-n", self.netns, "-s", "-j", "link", "show", self.veth],
                             capture_output=True, text=True).stdout
        stats = json.loads(out)[0]["stats64"]
        return int(stats["rx"]["bytes"]) + int(stats["tx"]["bytes"])

    def command(self, argv: list[str]) -> list[str]:
        return ["ip", "netns", "exec", self.netns, *argv]

    def env(self, base: dict, domain_id: int) -> dict:
        env = dict(base)
        env.update(FASTDDS_DEFAULT_PROFILES_FILE=self.profile_path,
                   FASTRTPS_DEFAULT_PROFILES_FILE=self.profile_path,
                   ROS_DOMAIN_ID=str(domain_id), RMW_IMPLEMENTATION="rmw_fastrtps_cpp",
                   # SUBNET: rmw leaves the profile's transports alone (LOCALHOST would confine
                   # DDS to the loopback, which here is each namespace's own and private)
                   ROS_AUTOMATIC_DISCOVERY_RANGE="SUBNET", PYTHONUNBUFFERED="1")
        env.pop("ROS_STATIC_PEERS", None)
        return env


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True)


def _wait_until_running(netns: str, dev: str, timeout_s: float = 10.0) -> None:
    """Wait until a veth end has carrier (operstate UP): `link set up` returns before the pair's
    carrier comes, and Fast DDS started earlier finds no usable interface for its whitelisted
    address ("All whitelist interfaces were filtered out") and never talks to the other host."""
    deadline = time.monotonic() + timeout_s
    while True:
        out = subprocess.run(["ip", "-n", netns, "-j", "link", "show", dev],
                             capture_output=True, text=True).stdout
        try:
            state = json.loads(out)[0].get("operstate")
        except (ValueError, IndexError):
            state = None
        if state == "UP":
            return
        if time.monotonic() > deadline:
            raise RuntimeError(f"veth {dev} in namespace {netns} has no carrier after {timeout_s:g} s "
                               f"(operstate {state})")
        time.sleep(0.02)


@contextmanager
def two_hosts(workdir: str, subnet_index: int | None = None):
    """Namespaces A and B joined by a veth pair; removed again whatever happens."""
    tag = uuid.uuid4().hex[:6]
    n = subnet_index if subnet_index is not None else int(tag, 16) % 200 + 20
    names = (f"bmA{tag}", f"bmB{tag}")
    addrs = (SUBNET.format(n=n, host=1), SUBNET.format(n=n, host=2))
    veths = (f"va{tag}", f"vb{tag}")
    made = []
    try:
        for name in names:
            _ip("netns", "add", name)
            made.append(name)
            _ip("-n", name, "link", "set", "lo", "up")
        _ip("link", "add", veths[0], "netns", names[0], "type", "veth", "peer", "name", veths[1],
            "netns", names[1])
        hosts = []
        for name, veth, own, peer in zip(names, veths, addrs, reversed(addrs)):
            _ip("-n", name, "addr", "add", f"{own}/24", "dev", veth)
            _ip("-n", name, "link", "set", veth, "up")
            path = os.path.join(workdir, f"fastdds_{name}.xml")
            with open(path, "w", encoding="utf-8") as f:
                f.write(fast_dds_profile(own, peer))
            hosts.append(Host(name, own, path, veth))
        for host in hosts:
            _wait_until_running(host.netns, host.veth)
        yield hosts[0], hosts[1]
    finally:
        for name in made:     # deleting a namespace deletes its end of the veth pair, and so both
            subprocess.run(["ip", "netns", "del", name], capture_output=True)


def run_two_hosts(workdir: str, base_env: dict, domain_id: int, duration_s: float = 5.0,
                  rate_factor: float = 1.0, namespace: str = "/line1/drive01",
                  timeout_s: float = 120.0) -> dict:
    """Plant and monitor on host A, the chain on host B; returns the monitor's counts plus
    ``delivered`` = onset estimates received on A / onset windows captured on B that the
    classifier classifies (all but those before the sensor offset was known), and the hosts'
    outputs under ``logs``."""
    exe = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")
    drive = namespace.strip("/")
    ros = ["--ros-args", "-r", f"__ns:={namespace}", "-p", f"drive_name:={drive}",
           "-p", "qos:=reliable"]
    with two_hosts(workdir) as (a, b):
        env_a, env_b = a.env(base_env, domain_id), b.env(base_env, domain_id)
        procs = {}
        try:
            procs["monitor"] = subprocess.Popen(
                a.command([sys.executable, "-m", "backlash_monitor.nodes.two_host_monitor",
                           namespace, str(timeout_s - 10.0)]), env=env_a,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            procs["chain"] = subprocess.Popen(
                b.command([os.path.join(exe, "chain"), *ros]), env=env_b,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            procs["plant"] = subprocess.Popen(
                a.command([os.path.join(exe, "plant_simulator"), *ros,
                           "-p", f"duration_s:={duration_s}", "-p", f"rate_factor:={rate_factor}",
                           "-p", "wait_for_subscribers:=['windowing:a1,a2,angle_difference']",
                           # discovery across the veth pair is slower: let host B match back
                           "-p", "match_settle_s:=1.0"]), env=env_a,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            out, _ = procs["monitor"].communicate(timeout=timeout_s)
        finally:
            for p in procs.values():
                if p.poll() is None:
                    p.terminate()
            logs = {}
            for name, p in procs.items():
                try:
                    logs[name] = p.communicate(timeout=15)[0] or ""
                except subprocess.TimeoutExpired:
                    p.kill()
                    logs[name] = p.communicate()[0] or ""
        veth_bytes = a.veth_bytes()
        lines = [line for line in (out or "").splitlines() if line.startswith("{")]
        result = json.loads(lines[-1]) if lines else {"onsets_estimated": 0, "onset_windows": 0}
        classifiable = result["onset_windows"] - result.get("onsets_before_offset", 0)
        result["delivered"] = result["onsets_estimated"] / classifiable if classifiable > 0 else 0.0
        result["addresses"] = [a.address, b.address]
        result["veth_bytes"] = veth_bytes
        result["logs"] = {**logs, "monitor": out}
        return result
