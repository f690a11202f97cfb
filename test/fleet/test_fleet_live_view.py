"""live_view: a WebSocket client speaking Foxglove's protocol subscribes to a drive's estimates and
its width, and receives what the drive publishes (the CDR bytes decode to the same estimate)."""
import asyncio
import json
import re
import struct
import subprocess
import sys
import time

import pytest

pytest.importorskip("foxglove", reason="the Foxglove SDK is an optional extra (pip install "
                                       "foxglove-sdk)")
websockets = pytest.importorskip("websockets", reason="the test's WebSocket client (pip install "
                                                      "websockets)")


@pytest.mark.process
@pytest.mark.ros
def test_a_foxglove_client_receives_a_drives_estimates_and_width(ros_env, monkeypatch):
    for key in ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE"):
        monkeypatch.setenv(key, ros_env[key])
    view = subprocess.Popen([sys.executable, "-m", "backlash_monitor.nodes.live_view", "--ros-args",
                             "-p", "namespaces:=[/line1/drive01]", "-p", "port:=0"],
                            env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    import rclpy
    from rclpy.serialization import deserialize_message
    from backlash_monitor.ros.qos import ESTIMATE_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("drive_stand_in", context=context)
    publisher = node.create_publisher(BacklashEstimate, "/line1/drive01/estimate", ESTIMATE_QOS)
    try:
        port = None
        deadline = time.monotonic() + 60
        while port is None and time.monotonic() < deadline:
            line = view.stdout.readline()
            match = re.search(r"ws://[\d.]+:(\d+)", line)
            port = int(match.group(1)) if match else None
        assert port, "live_view did not report its port"
        while publisher.get_subscription_count() == 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        sent = []

        def publish_estimates():   # once the client has subscribed: the view is live
            for i in range(5):
                msg = BacklashEstimate(signal_name="a1+a2", mode="shape",
                                       entry_sample_index=2700 + i, entry_kind="onset",
                                       width_m=0.0075, fused_width_m=0.0075,
                                       continuous_width_m=0.0074, fused_events=i + 1,
                                       true_width_m=0.0075)
                msg.header.frame_id = "line1/drive01"
                publisher.publish(msg)
                sent.append(msg)
        received = asyncio.run(_foxglove_client(port, ["/line1/drive01/estimate",
                                                       "/line1/drive01/width"], count=4,
                                                on_subscribed=publish_estimates))
    finally:
        node.destroy_node()
        rclpy.shutdown(context=context)
        view.terminate()
        out = view.communicate(timeout=20)[0]
    assert "Traceback" not in out, out
    estimates = [deserialize_message(p, BacklashEstimate)
                 for topic, p in received if topic == "/line1/drive01/estimate"]
    widths = [json.loads(p) for topic, p in received if topic == "/line1/drive01/width"]
    assert estimates and widths, received
    for got in estimates:
        assert got.entry_sample_index in {m.entry_sample_index for m in sent}
        assert got.width_m == 0.0075 and got.header.frame_id == "line1/drive01"
    assert widths[-1]["fused_width_mm"] == pytest.approx(7.5)
    assert widths[-1]["drive"] == "line1/drive01"


async def _foxglove_client(port, topics, count, on_subscribed, timeout_s=30.0):
    """Foxglove's WebSocket protocol (subprotocol foxglove.sdk.v1, as the SDK's server asks; the
    same messages as foxglove.websocket.v1): serverInfo and advertise come as JSON text frames; the
    client subscribes by channel id; each message is a binary frame: opcode 1, subscription id
    (uint32 LE), log time (uint64 LE), payload."""
    received = []
    async with websockets.connect(f"ws://127.0.0.1:{port}",
                                  subprotocols=["foxglove.sdk.v1"]) as ws:
        channels, subscribed = {}, {}
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline and len(received) < count:
            frame = await asyncio.wait_for(ws.recv(), timeout=max(0.1, deadline - time.monotonic()))
            if isinstance(frame, str):
                op = json.loads(frame)
                if op.get("op") == "advertise":
                    channels.update({c["topic"]: c["id"] for c in op["channels"]})
                    wanted = [{"id": i + 1, "channelId": channels[t]}
                              for i, t in enumerate(topics) if t in channels and
                              (i + 1) not in subscribed]
                    if wanted:
                        await ws.send(json.dumps({"op": "subscribe", "subscriptions": wanted}))
                        subscribed.update({w["id"]: topics[w["id"] - 1] for w in wanted})
                    if len(subscribed) == len(topics):
                        await asyncio.sleep(0.5)    # the server takes the subscription
                        on_subscribed()
                continue
            if frame[0] == 1:
                sub_id, = struct.unpack_from("<I", frame, 1)
                received.append((subscribed[sub_id], bytes(frame[13:])))
    return received


@pytest.mark.ros
def test_the_foxglove_layout_plots_fields_the_live_view_serves():
    """Every path in config/foxglove_fleet_layout.json names a topic live_view serves for
    `fleet --drives 4` and a field of that topic's message (or of the width JSON)."""
    import pathlib
    from backlash_monitor.bag.schema import local_specs
    from backlash_monitor.nodes.live_view import FORWARDED, WIDTH_SCHEMA
    layout = json.loads((pathlib.Path(__file__).resolve().parents[2] / "config"
                         / "foxglove_fleet_layout.json").read_text())
    fields = {}
    for ns in (f"/line1/drive{i:02d}" for i in range(1, 5)):
        for topic, type_name, _ in FORWARDED:
            spec = local_specs(type_name)[type_name]
            fields[f"{ns}/{topic}"] = {f.name for f in spec.fields}
        fields[f"{ns}/width"] = set(WIDTH_SCHEMA["properties"])
    paths = [p["value"] for panel in layout["configById"].values() for p in panel.get("paths", [])]
    assert len(paths) >= 8
    for path in paths:
        topic, field = path.rsplit(".", 1)
        assert field in fields.get(topic, set()), path
    panels = set(layout["configById"])
    def leaves(node):
        return {node} if isinstance(node, str) else leaves(node["first"]) | leaves(node["second"])
    assert leaves(layout["layout"]) == panels
