"""The Fast DDS writer profile of this project's processes.

Fast DDS sends a reliable writer's heartbeat every 3 s by default, and a reader asks for a lost
sample again only in answer to a heartbeat. A chunk lost in the loopback transport during a burst
(a replay at full speed, a stream faster than real time) then stalls that topic for up to 3 s,
and the windowing behind it with it. The profile below asks for a heartbeat every 10 ms on this
process's writers; nothing else changes. A profile file the user set
(FASTDDS_DEFAULT_PROFILES_FILE or FASTRTPS_DEFAULT_PROFILES_FILE) is left alone.
"""
from __future__ import annotations

import os
import tempfile

# The writers' profile (the heartbeat period, docs/graph.md); other profiles embed it too.
WRITER_PROFILE_XML = """  <data_writer profile_name="backlash_monitor_writer" is_default_profile="true">
    <times>
      <heartbeatPeriod><sec>0</sec><nanosec>10000000</nanosec></heartbeatPeriod>
    </times>
  </data_writer>
"""

FAST_DDS_PROFILE = ("""<?xml version="1.0" encoding="UTF-8" ?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
""" + WRITER_PROFILE_XML + """</profiles>
""")


def configure_fast_dds() -> None:
    """Point Fast DDS at the project's writer profile; call before rclpy.init()."""
    if os.environ.get("FASTRTPS_DEFAULT_PROFILES_FILE") or os.environ.get(
            "FASTDDS_DEFAULT_PROFILES_FILE"):
        return
    path = os.path.join(tempfile.gettempdir(), f"backlash_monitor_fastdds_{os.getuid()}.xml")
    try:
        if not os.path.isfile(path) or open(path, encoding="utf-8").read() != FAST_DDS_PROFILE:
            with open(path + f".{os.getpid()}.tmp", "w", encoding="utf-8") as f:
                f.write(FAST_DDS_PROFILE)
            os.replace(path + f".{os.getpid()}.tmp", path)
    except OSError:
        return
    os.environ["FASTRTPS_DEFAULT_PROFILES_FILE"] = path
