"""The Fast DDS writer profile of this project's processes.

Fast DDS sends a reliable writer's heartbeat every 3 s by default, and a reader asks for a lost
sample again only in answer to a heartbeat. A chunk lost in the loopback transport during a burst
(a replay at full speed, a stream faster than real time) then stalls that topic for up to 3 s,
and the windowing behind it with it. The profile below asks for a heartbeat every 10 ms on this
process's writers; nothing else changes. A profile file the user set
(FASTDDS_DEFAULT_PROFILES_FILE or FASTRTPS_DEFAULT_PROFILES_FILE) is left alone.

On a graph kept to this machine (``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) the profile also gives each
participant one unicast locator, UDPv4 on 127.0.0.1, so that its endpoints are reached over loopback UDP and
not through Fast DDS's shared-memory ports (rmw_fastrtps adds the shared-memory transport for that range with its
default settings; no profile can change them). A shared-memory port is judged dead by the other processes'
watchdogs when its listener stops for longer than 1 s (a stalled or killed process): it is regenerated, and
twice in a full test run a hop's data stopped for good after a process of the graph was stopped or killed
(docs/graph.md "Loopback UDP, not shared memory"). Over UDP a stopped reader's socket overflows and the writer's
heartbeat repairs what it lost. Other ranges keep Fast DDS's default locators (a graph over several hosts).
"""
from __future__ import annotations

import hashlib
import os
import tempfile

# The writers' profile (the heartbeat period, docs/graph.md); other profiles embed it too.
WRITER_PROFILE_XML = """  <data_writer profile_name="backlash_monitor_writer" is_default_profile="true">
    <times>
      <heartbeatPeriod><sec>0</sec><nanosec>10000000</nanosec></heartbeatPeriod>
    </times>
  </data_writer>
"""

# Each participant's unicast locator on a loopback-only graph: UDPv4 on 127.0.0.1 (its port from the domain and the
# participant's id, as Fast DDS numbers them), so no endpoint is announced on a shared-memory port.
LOOPBACK_PARTICIPANT_XML = """  <participant profile_name="backlash_monitor_loopback_udp" is_default_profile="true">
    <rtps>
      <defaultUnicastLocatorList>
        <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
      </defaultUnicastLocatorList>
    </rtps>
  </participant>
"""

HEADER_XML = """<?xml version="1.0" encoding="UTF-8" ?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
"""

FAST_DDS_PROFILE = HEADER_XML + WRITER_PROFILE_XML + "</profiles>\n"
LOOPBACK_FAST_DDS_PROFILE = HEADER_XML + LOOPBACK_PARTICIPANT_XML + WRITER_PROFILE_XML + "</profiles>\n"


def profile_for_range(discovery_range: str | None) -> str:
    """The project's profile for a ROS_AUTOMATIC_DISCOVERY_RANGE value: on LOCALHOST the loopback UDP locator too."""
    return LOOPBACK_FAST_DDS_PROFILE if (discovery_range or "").strip().upper() == "LOCALHOST" else FAST_DDS_PROFILE


def profile_env(env) -> None:
    """Point ``env`` (os.environ or a child process's environment) at the project's profile for its
    ROS_AUTOMATIC_DISCOVERY_RANGE (written once into the temporary directory, named by its content), unless it names a profile
    file already (FASTRTPS_/FASTDDS_DEFAULT_PROFILES_FILE: the user's, left alone)."""
    if env.get("FASTRTPS_DEFAULT_PROFILES_FILE") or env.get("FASTDDS_DEFAULT_PROFILES_FILE"):
        return
    profile = profile_for_range(env.get("ROS_AUTOMATIC_DISCOVERY_RANGE"))
    digest = hashlib.sha256(profile.encode()).hexdigest()[:12]      # named by its content: never rewritten
    path = os.path.join(tempfile.gettempdir(), f"backlash_monitor_fastdds_{digest}_{os.getuid()}.xml")
    try:
        if not os.path.isfile(path):
            with open(path + f".{os.getpid()}.tmp", "w", encoding="utf-8") as f:
                f.write(profile)
            os.replace(path + f".{os.getpid()}.tmp", path)
    except OSError:
        return
    env["FASTRTPS_DEFAULT_PROFILES_FILE"] = path


def configure_fast_dds() -> None:
    """Point Fast DDS at the project's profile (the writers' heartbeat; on LOCALHOST the loopback UDP locator);
    call before rclpy.init()."""
    profile_env(os.environ)
