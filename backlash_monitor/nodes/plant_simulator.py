"""plant_simulator: the paper's drive (SPEC section 3) streamed at 50 kHz as SignalChunk messages.

    ros2 run backlash_monitor plant_simulator --ros-args -p width_m:=0.005 -p rate_factor:=1.0

Publishes, per chunk of ``chunk_samples`` samples, one SignalChunk on each of ``plant/a1``,
``plant/a2``, ``plant/omega1``, ``plant/omega2`` and (the encoders' measurement)
``plant/angle_difference``, with sensor-data QoS by default; and the simulated width, latched, on
``plant/true_width_m`` (std_msgs/Float64) so that downstream nodes can report it. Chunks are
stamped with the time of their first sample and indexed by ``first_sample_index``.
"""
from __future__ import annotations

import sys
import time

from rclpy.node import Node
from rclpy.qos import QoSCompatibility, qos_check_compatible
from std_msgs.msg import Float64

from backlash_monitor.ros.delivery import wait_acknowledged
from backlash_monitor.ros.conversions import SIGNAL_UNITS, stamp_of_sample, to_float64_array
from backlash_monitor.ros.parameters import ParameterSpec, declare_and_validate, ParameterValueError
from backlash_monitor.ros.qos import LATCHED, chunk_qos
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.plant import Scenario, PlantSimulator, load_plant_config, builtin_catalogue
from backlash_monitor.plant.integrator import BACKENDS
from backlash_monitor.process.subscriber_wait import TopicState, fully_qualified, missing, parse_wanted
from backlash_monitor.plant.config import parse_override
from backlash_monitor.plant.simulate import check_runtime_change
from backlash_monitor_msgs.msg import SignalChunk
import rclpy

TICK_PERIOD_S = 0.01      # the publishing timer; each tick publishes every chunk that is due
MAX_CHUNKS_PER_TICK = 64  # bound on the catch-up after a stall

PARAMETERS = (
    ParameterSpec("drive_name", "drive", "the drive's name: frame_id of every message"),
    ParameterSpec("width_m", 0.005, "backlash width K2 of the simulated clutch [m]", 1e-4, 0.05),
    ParameterSpec("eta_k", 0.025, "absorber fluid consistency [Pa*s^n]", 1e-4, 1.0),
    ParameterSpec("n1", 0.89, "absorber fluid flow (creep) index [-]", 0.5, 1.5),
    ParameterSpec("seed", 0, "seed of the disturbance generators", 0, 2**31 - 1),
    ParameterSpec("noise", True, "Gaussian and pulse disturbances on the load moment"),
    ParameterSpec("plant_config", "", "plant YAML (empty: the packaged config/plant.yaml)"),
    ParameterSpec("plant_set", "", "plant config overrides 'SECTION.KEY=VALUE' separated by ';', as simulate's "
                  "--set (e.g. 'effects.wheel_coulomb_friction=true;wheel_coulomb_friction.torque_Nm=1.5')"),
    ParameterSpec("plant_set_at", [""], "run-time plant changes, each 'T_S:SECTION.KEY=VALUE;...' (e.g. "
                  "'30:effects.wheel_coulomb_friction=true;wheel_coulomb_friction.torque_Nm=1.5'): from simulated "
                  "second T_S on, the plant runs with these overrides too (an effect switched on then is on from "
                  "the start at its neutral default); [''] = none"),
    ParameterSpec("effects_files", "", "Python files with your own Effect classes, separated by ';' "
                  "(docs/effects.md; as --effects-file of simulate and pipeline)"),
    ParameterSpec("chunk_samples", 1000, "samples per chunk (1000 = 20 ms at 50 kHz)", 64, 50000),
    ParameterSpec("rate_factor", 1.0, "simulated seconds per wall second (1 = real time; "
                  "0 = as fast as the simulation runs)", 0.0, 1000.0),
    ParameterSpec("duration_s", 0.0, "simulated seconds to publish, then stop (0 = forever)",
                  0.0, 1e7),
    ParameterSpec("qos", "sensor_data", "QoS of the chunk topics",
                  choices=("sensor_data", "reliable")),
    ParameterSpec("finish_timeout_s", 10.0, "once duration_s is published: wait up to this long for every reliable "
                  "subscriber to acknowledge every chunk before the node exits (a subscriber behind the stream -- "
                  "stalled, loaded, across a network -- still gets its end: a reliable chunk still in the "
                  "publisher's history is lost with the process); 0 = exit at once; with qos sensor_data there is "
                  "nothing to wait for [s]", 0.0, 3600.0),
    ParameterSpec("backend", "numba-scalar", "integrator kernel for the one simulated drive: "
                  "'numba-scalar' (3x faster per chunk than 'numba', whose SIMD kernel computes "
                  "8 lanes for one drive; the same RK4 scheme, results agree with a batch run to "
                  "~1e-13 relative, not bit for bit), 'numba', 'numpy' or 'auto' (config)",
                  choices=BACKENDS),
    ParameterSpec("wait_for_subscriptions", 0, "start the stream only once the chunk topics have "
                  "this many matched subscriptions in total (any subscriber counts; prefer "
                  "wait_for_subscribers, which names the ones the stream is for)", 0, 1000),
    ParameterSpec("wait_for_subscribers", [""], "start the stream only once these nodes subscribe: "
                  "'NODE:SIGNAL,SIGNAL' (e.g. 'windowing:a1,a2,angle_difference') or 'NODE' (all "
                  "five signals); NODE relative to this node's namespace or absolute; [''] = none"),
    ParameterSpec("wait_timeout_s", 60.0, "how long to wait for wait_for_subscribers before "
                  "streaming anyway (logged as a warning naming who is missing); 0 = no limit [s]",
                  0.0, 86400.0),
    ParameterSpec("match_settle_s", 0.25, "once the awaited subscriptions are matched, wait this long "
                  "more before streaming: the publisher sees the match before the subscriber has "
                  "matched back, and a volatile subscriber drops what was sent before its side "
                  "matched (the stream's first chunk, seen across two hosts) [s]", 0.0, 60.0),
)

def parse_set_at(entries) -> list:
    """['T_S:KEY=VALUE;KEY=VALUE', ...] -> [(T_S, {key: value})] in time order; ValueError naming a bad entry."""
    out = []
    for entry in entries:
        if not entry.strip():
            continue
        head, sep, rest = entry.partition(":")
        try:
            t_s = float(head.strip().rstrip("s"))
        except ValueError:
            t_s = -1.0
        if not sep or not (t_s >= 0.0 and t_s < 1e7) or not rest.strip():
            raise ValueError(f"parameter 'plant_set_at' entry {entry!r}: allowed: 'T_S:SECTION.KEY=VALUE;...' with "
                             "0 <= T_S simulated seconds, e.g. '30:effects.wheel_coulomb_friction=true'")
        out.append((t_s, dict(parse_override(t) for t in rest.split(";") if t.strip())))
    return sorted(out, key=lambda x: x[0])


class PlantSimulatorNode(Node):
    def __init__(self, **overrides):
        super().__init__("plant_simulator", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        self.params = p
        try:
            catalogue = builtin_catalogue().with_files(
                [x.strip() for x in p["effects_files"].split(";") if x.strip()])
            overrides = dict(parse_override(t) for t in p["plant_set"].split(";") if t.strip())
            self.set_at = parse_set_at(p["plant_set_at"])
            # an effect switched on later is on from the start, at its neutral default (one compiled kernel)
            switches = {k: v for _, changes in self.set_at for k, v in changes.items()
                        if k.startswith("effects.") and v is True}
            config = load_plant_config(p["plant_config"] or None, overrides={**switches, **overrides} or None,
                                       catalogue=catalogue)
            # the configs of the changes, checked now (a bad one stops the node at start, not mid-run)
            self.set_at_configs = []
            applied = dict(switches)
            for t_s, changes in self.set_at:
                applied.update(changes)
                self.set_at_configs.append((t_s, changes, load_plant_config(
                    p["plant_config"] or None, overrides={**applied, **overrides}, catalogue=catalogue)))
            scenario = Scenario(width_m=p["width_m"], eta_k=p["eta_k"], n1=p["n1"], seed=p["seed"])
            self.simulator = PlantSimulator([scenario], config=config, noise=p["noise"],
                                            outputs=tuple(SIGNAL_UNITS),
                                            backend=None if p["backend"] == "auto" else p["backend"])
            for _t, _changes, cfg in self.set_at_configs:
                check_runtime_change(config, cfg)
        except ValueError as error:
            raise ParameterValueError(str(error)) from None
        self.sample_period_s = self.simulator.sample_period_s
        qos = chunk_qos(p["qos"])
        self.publishers_by_signal = {name: self.create_publisher(SignalChunk, f"plant/{name}", qos)
                                     for name in SIGNAL_UNITS}
        self.width_publisher = self.create_publisher(Float64, "plant/true_width_m", LATCHED)
        self.width_publisher.publish(Float64(data=float(p["width_m"])))
        self.total_chunks = (int(round(p["duration_s"] / self.sample_period_s / p["chunk_samples"]))
                             if p["duration_s"] > 0 else None)
        self.chunks_published = 0
        self.started = False
        self.finished = False
        try:
            self.wanted = parse_wanted(p["wait_for_subscribers"], self.get_namespace(),
                                       SIGNAL_UNITS)
        except ValueError as error:
            raise ParameterValueError(f"parameter {error}") from None
        self.chunk_qos = qos
        self.wait_started = time.monotonic()
        self.matched_at_s: float | None = None   # when the awaited subscriptions were all matched
        if self.wanted:
            limit = f"up to {p['wait_timeout_s']:g} s" if p["wait_timeout_s"] > 0 else "no limit"
            self.get_logger().info(
                "waiting for subscribers before streaming (" + limit + "): "
                + "; ".join(f"{w.node} on {', '.join(w.signals)}" for w in self.wanted))
        self.timer = self.create_timer(TICK_PERIOD_S, self.on_tick)
        self.get_logger().info(
            f"simulating {p['drive_name']}: width {p['width_m'] * 1e3:g} mm, eta_k {p['eta_k']:g}, "
            f"n1 {p['n1']:g}, {p['chunk_samples']} samples/chunk at x{p['rate_factor']:g} real time")

    def due_chunks(self) -> int:
        rate = self.params["rate_factor"]
        if rate == 0.0:
            due = MAX_CHUNKS_PER_TICK
        else:
            simulated_s = (time.monotonic() - self.wall_start) * rate
            due = int(simulated_s / (self.sample_period_s * self.params["chunk_samples"])) \
                - self.chunks_published
        if self.total_chunks is not None:
            due = min(due, self.total_chunks - self.chunks_published)
        return max(0, min(due, MAX_CHUNKS_PER_TICK))

    def missing_subscribers(self) -> list[str]:
        """What the stream still waits for ([] = nothing): the named subscribers
        (subscriber_wait.py), then the legacy total count."""
        topics = {}
        for signal in {s for w in self.wanted for s in w.signals}:
            pub = self.publishers_by_signal[signal]
            infos = self.get_subscriptions_info_by_topic(pub.topic_name)
            topics[signal] = TopicState(
                frozenset(fully_qualified(i.node_name, i.node_namespace) for i in infos),
                sum(1 for i in infos if qos_check_compatible(self.chunk_qos, i.qos_profile)[0]
                    != QoSCompatibility.ERROR),
                pub.get_subscription_count())
        out = missing(self.wanted, topics)
        matched = sum(pub.get_subscription_count() for pub in self.publishers_by_signal.values())
        if matched < self.params["wait_for_subscriptions"]:
            out.append(f"{matched} of {self.params['wait_for_subscriptions']} subscriptions")
        return out

    def start_stream(self) -> bool:
        """Start the clock of the stream once the required subscribers are there (or the wait
        timed out: then say who is missing)."""
        absent = self.missing_subscribers()
        if absent:
            self.matched_at_s = None
            timeout = self.params["wait_timeout_s"]
            if timeout <= 0 or time.monotonic() - self.wait_started < timeout:
                return False
            self.get_logger().warning(f"streaming without them after waiting {timeout:g} s for "
                                      f"subscribers: missing {'; '.join(absent)} (they lose the "
                                      "stream's start)")
        elif self.wanted or self.params["wait_for_subscriptions"]:
            now = time.monotonic()
            if self.matched_at_s is None:
                self.matched_at_s = now
            if now - self.matched_at_s < self.params["match_settle_s"]:
                return False
            self.get_logger().info(f"subscribers there after {self.matched_at_s - self.wait_started:.1f} s: "
                                   "streaming")
        self.stream_start_s = self.get_clock().now().nanoseconds * 1e-9
        self.wall_start = time.monotonic()
        self.started = True
        return True

    def on_tick(self):
        if not self.started and not self.start_stream():
            return
        for _ in range(self.due_chunks()):
            self.publish_chunk()
        if self.total_chunks is not None and self.chunks_published >= self.total_chunks \
                and not self.finished:
            self.finished = True
            self.timer.cancel()
            self.get_logger().info(f"published {self.chunks_published} chunks "
                                   f"({self.chunks_published * self.params['chunk_samples'] * self.sample_period_s:g} s)")

    def apply_changes(self) -> None:
        """The plant_set_at changes whose time has come (at the first chunk that starts at or after it)."""
        t = self.simulator.sample_index * self.sample_period_s
        while self.set_at_configs and self.set_at_configs[0][0] <= t + 1e-12:
            t_s, changes, cfg = self.set_at_configs.pop(0)
            self.simulator.set_config(cfg)
            self.get_logger().info(f"at t = {t:.3f} s (sample {self.simulator.sample_index}): "
                                   + ", ".join(f"{k}={v}" for k, v in changes.items()))

    def publish_chunk(self):
        if self.set_at_configs:
            self.apply_changes()
        chunk = self.simulator.run(self.params["chunk_samples"])
        stamp = stamp_of_sample(self.stream_start_s, chunk.first_sample_index, self.sample_period_s)
        for name, publisher in self.publishers_by_signal.items():
            msg = SignalChunk()
            msg.header.stamp = stamp
            msg.header.frame_id = self.params["drive_name"]
            msg.signal_name = name
            msg.unit = SIGNAL_UNITS[name]
            msg.sample_period_s = self.sample_period_s
            msg.first_sample_index = chunk.first_sample_index
            msg.samples = to_float64_array(getattr(chunk, name)[0])
            publisher.publish(msg)
        self.chunks_published += 1

    def wait_delivered(self) -> bool:
        """After the last chunk: wait (up to finish_timeout_s) until every subscriber of the chunk topics has
        acknowledged every chunk; False, with a warning naming the topics, when one has not (best-effort topics
        acknowledge nothing: True at once)."""
        timeout_s = self.params["finish_timeout_s"]
        if timeout_s <= 0:
            return True
        behind = wait_acknowledged({f"plant/{name}": pub for name, pub in self.publishers_by_signal.items()},
                                   timeout_s)
        if behind:
            self.get_logger().warning(f"exiting with chunks not acknowledged after {timeout_s:g} s on "
                                      f"{', '.join(behind)}: a subscriber still behind the stream loses its end "
                                      "(raise finish_timeout_s to wait longer)")
        return not behind


def main(args=None):
    def spin(node, executor):
        while rclpy.ok() and not node.finished:
            executor.spin_once(timeout_sec=0.1)
        if node.finished:
            node.wait_delivered()
    return run_node(PlantSimulatorNode, args=args, spin=spin)


if __name__ == "__main__":
    sys.exit(main())
