"""model_watch: is the drive still what its model version says? The workbench's consistency test, live.

    ros2 run backlash_monitor model_watch --ros-args -r __ns:=/line1/drive7 -p drive_name:=line1/drive7 \\
        -p reference:=drive7_v3.watch.npz

One per drive, in its namespace beside the classifier. Subscribes to the drive's ``plant/a1``, ``a2``,
``angle_difference`` and ``omega1`` (``snapshot_signals``; ``omega2`` too if asked) as serialized messages; the
events' record mean takes the motor speed omega1 beside a1 and a2 (``watch_omega1``: diagnose's record-mean view,
the drive's load); the core
(backlash_monitor/watch/: the live onset events, ModelWatch, the alarm rule) evaluates the model version's
precomputed reference (workbench/reference.py: no simulation here) on the last ``window_events`` onset events after
every event, and the node publishes:
- ``model_fit`` (backlash_monitor_msgs/ModelFit): residual over noise per signal, T^2 per view, the width the model
  is compared at, where the residual sits;
- on ``/diagnostics``, status ``<node>: model fit``, hardware_id = the drive's name: OK "model drive7 v3 explains the
  drive (residual 0.9x the noise floor)", or WARN "model drive7 v3 no longer explains the drive since 12:03:11:
  residual 2.8x the noise floor, in the gap traversal, wavelet level d4; snapshot drive7_20261124T120311.mcap; run
  diagnose on it"; STALE when the stream stopped for ``stale_after_s``;
- with ``watch_omega1``, a1 checked against the motor speed (windowing/a1_chain.py: a1 = r·dΩ₁/dt): where a1 does not
  follow it, the status is WARN and says so ("a1 does not follow r·dΩ₁/dt ...: the widths read from a1 and a1+a2
  are not to be trusted"), value ``a1_chain_mismatch`` (docs/classifier.md 5.4);
- on a WARN, a snapshot: an ordinary project bag of the plant topics from ``snapshot_before_s`` before to
  ``snapshot_after_s`` after it, in ``snapshot_dir`` (watch/snapshot.py: never overwritten, written in a thread).

Bad chunks (not SignalChunk, non-finite samples, gaps) are dropped and counted as the windowing does; the events they
cut are not evaluated. docs/model_watch.md.
"""
from __future__ import annotations

import datetime as _dt
import math
import os
import sys
import time

from rclpy.node import Node
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from backlash_monitor_msgs.msg import ModelFit, SignalChunk

from backlash_monitor.windowing.a1_chain import A1ChainCheck
from backlash_monitor.windowing.faults import FaultLog, InputHealth
from backlash_monitor.ros.conversions import to_float64_array, time_from_seconds
from backlash_monitor.ros.drive_diagnostics import DriveDiagnostics
from backlash_monitor.ros.parameters import ParameterSpec, ParameterValueError, declare_and_validate
from backlash_monitor.ros.qos import CHUNK_QOS_CHOICES, chunk_qos
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.watch.alarm import load_config, AlarmRule
from backlash_monitor.workbench import reference as ref_mod
from backlash_monitor.bag.cdr import Codec
from backlash_monitor.chain.joiner import ChunkJoiner, pending_ranges_for
from backlash_monitor.stream_time import sample_time_s, stamp_seconds, stream_origin_s
from backlash_monitor.watch.core import ModelWatch
from backlash_monitor.workbench.events import DC_SIGNALS, SEGMENT_SIGNALS
from backlash_monitor.watch.snapshot import SIGNAL_CHUNK, SnapshotRecorder

WATCHED = ("a1", "a2", "angle_difference")           # the streams every watch joins; with watch_omega1 also omega1
PLANT_SIGNALS = ("a1", "a2", "omega1", "omega2", "angle_difference")
MODEL_FIT_QOS = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)


def _parameters():
    c = load_config()
    return (
        ParameterSpec("drive_name", "drive", "the drive's name: diagnostics hardware_id, frame_id, snapshot names"),
        ParameterSpec("reference", "", "the model version's reference (LIB.watch.npz, written by `train --model`); "
                      "empty: the default model's at width_m, eta_k, n1 from the cache (`python -m "
                      "backlash_monitor watch-reference` builds it)"),
        ParameterSpec("width_m", 0.005, "with reference empty: the default model's nominal backlash width [m]",
                      1e-4, 0.05),
        ParameterSpec("eta_k", 0.025, "with reference empty: the default model's absorber consistency [Pa*s^n]",
                      1e-4, 1.0),
        ParameterSpec("n1", 0.89, "with reference empty: the default model's absorber flow index [-]", 0.5, 1.5),
        ParameterSpec("window_events", c["window_events"], "onset events each evaluation takes (the last ones)",
                      3, 1000),
        ParameterSpec("view_p", c["view_p"], "alarm: a consistency view exceeds below this chance of its T^2 from "
                      "the model's own noise", 1e-15, 0.1),
        ParameterSpec("residual_ratio", c["residual_ratio"], "alarm: ... or the event average's residual above "
                      "this many noise floors", 1.0, 100.0),
        ParameterSpec("persistence", c["persistence"], "alarm: WARN after this many consecutive exceeding "
                      "evaluations", 1, 1000),
        ParameterSpec("clear_after", c["clear_after"], "alarm: OK again after this many consecutive evaluations "
                      "that do not exceed", 1, 100000),
        ParameterSpec("robust", c["robust"], "alarm: an evaluation exceeds only if it also does with any one of its "
                      "events left out"),
        ParameterSpec("event_clip_p", c["event_clip_p"] or 0.0, "alarm: an event's whitened deviation counts at most "
                      "at the length the model's own events exceed with this chance (bounded influence; 0: none)",
                      0.0, 0.1),
        ParameterSpec("predictive", c["predictive"], "alarm: the views' p-values from Hotelling's predictive law (the "
                      "whitening is estimated from the model's own events); false: chi^2"),
        ParameterSpec("watch_omega1", True, "the events' record mean takes the motor speed plant/omega1 beside a1 "
                      "and a2, as diagnose does on a recording that has it: a load on the motor (friction, a fan) "
                      "slows it and shows there, not in the accelerations; false for a drive that does not publish "
                      "omega1"),
        ParameterSpec("snapshot_dir", ".", "where the snapshot bags go (created if missing; empty: no snapshots)"),
        ParameterSpec("snapshot_before_s", c["snapshot_before_s"], "snapshot: seconds of the stream before the "
                      "WARN [s]", 0.0, 60.0),
        ParameterSpec("snapshot_after_s", c["snapshot_after_s"], "snapshot: seconds after it [s]", 0.5, 120.0),
        ParameterSpec("snapshot_signals", ["a1", "a2", "angle_difference", "omega1"], "the plant signals a "
                      "snapshot holds: diagnose reads a1, a2, angle_difference and omega1 (its record-mean view has "
                      "the motor's mean speed, the drive's load: without it diagnose on the snapshot sees less than "
                      "on a full recording); omega2 may be added"),
        ParameterSpec("max_snapshots", 20, "snapshots this node writes at most (a drive that goes WARN again and "
                      "again does not fill the disk; later WARNs say so)", 0, 100000),
        ParameterSpec("qos", "sensor_data", "QoS of the chunk subscriptions", choices=CHUNK_QOS_CHOICES),
        ParameterSpec("batch_s", 0.25, "run as its own process (ros2 run): seconds the chunks may collect before "
                      "they are taken, all at once (fewer wake-ups; a result comes at most this much later, about "
                      "one onset period; shorter when a queue fills; 0: each chunk at once; <= stale_after_s / 2)",
                      0.0, 0.5),
        ParameterSpec("stale_after_s", 2.0, "seconds without a chunk after which /diagnostics says STALE",
                      0.01, 3600.0),
        ParameterSpec("fault_hold_s", 10.0, "seconds /diagnostics says WARN after the last bad chunk", 0.01, 3600.0),
    )


def _load_reference(p):
    path = p["reference"]
    if not path:
        # deferred: the model (the simulator) costs ~500-1100 ms at start-up (python -X importtime, 29 Nov); only without a reference file
        from backlash_monitor.workbench.model import ModelError, load_model
        try:
            model = load_model(None, width_m=p["width_m"], eta_k=p["eta_k"], n1=p["n1"])
        except ModelError as error:
            raise ParameterValueError(str(error)) from None
        path = ref_mod.cache_path(model)
        if not path.is_file():
            raise ParameterValueError(
                f"no model reference for the default model at width {p['width_m'] * 1e3:g} mm, eta_k {p['eta_k']:g}, "
                f"n1 {p['n1']:g}: build it with `python -m backlash_monitor watch-reference --width-m {p['width_m']:g} "
                f"--eta-k {p['eta_k']:g} --n1 {p['n1']:g}` (~30 s, cached), or give the parameter 'reference'")
    try:
        return ref_mod.load(path)
    except ref_mod.ReferenceError as error:
        raise ParameterValueError(f"parameter 'reference': {error}") from None


class ModelWatchNode(Node):
    def __init__(self, **overrides):
        super().__init__("model_watch", **overrides)
        p = declare_and_validate(self, _parameters())
        if p["snapshot_before_s"] + p["snapshot_after_s"] > 180.0:
            raise ParameterValueError(f"snapshot_before_s + snapshot_after_s = "
                                      f"{p['snapshot_before_s'] + p['snapshot_after_s']:g} s; allowed: <= 180 s "
                                      "(the ring is held in memory: ~2 MB/s of stream)")
        if p["batch_s"] > p["stale_after_s"] / 2:
            raise ParameterValueError(f"batch_s = {p['batch_s']:g} s with stale_after_s = {p['stale_after_s']:g} s; "
                                      "allowed: batch_s <= stale_after_s / 2 (chunks held for a batch must not look "
                                      "like a stopped stream)")
        bad = [x for x in p["snapshot_signals"] if x not in PLANT_SIGNALS]
        self.watched = WATCHED + (("omega1",) if p["watch_omega1"] else ())
        if bad or not set(WATCHED) <= set(p["snapshot_signals"]):
            raise ParameterValueError(f"parameter 'snapshot_signals' = {list(p['snapshot_signals'])!r}; allowed: "
                                      f"a1, a2, angle_difference and any of omega1, omega2")
        if p["watch_omega1"] and "omega1" not in p["snapshot_signals"]:
            raise ParameterValueError(f"parameter 'snapshot_signals' = {list(p['snapshot_signals'])!r} without omega1 "
                                      "while watch_omega1 is true: a snapshot must hold what the watch saw; add "
                                      "omega1, or set watch_omega1 false")
        self.params = p
        self.executor_batch_s = p["batch_s"]          # run_node's executor batches the wake-ups (lean_executor)
        self.blas_threads = 1                          # run_node: its small products on one thread (process/blas)
        self.signals = tuple(n for n in PLANT_SIGNALS if n in p["snapshot_signals"])
        self.reference = _load_reference(p)
        try:
            rule = AlarmRule(p["view_p"], p["residual_ratio"], p["persistence"], p["clear_after"],
                             p["robust"], p["event_clip_p"] or None, p["predictive"]).check()
            self.watch = ModelWatch(self.reference, p["window_events"], rule,
                                    DC_SIGNALS if p["watch_omega1"] else SEGMENT_SIGNALS)
        except ValueError as error:
            raise ParameterValueError(str(error)) from None
        self.model = self.reference.model_label
        self.codec = Codec.for_type("backlash_monitor_msgs/msg/SignalChunk")
        self.strings = {name: [None] for name in self.signals}
        self.faults = FaultLog()
        # a range waits for its last chunk as long as that can still be queued (docs/graph.md)
        self.joiner = ChunkJoiner(self.watched, max_pending=pending_ranges_for(chunk_qos(p["qos"]).depth),
                                  faults=self.faults)
        self.health = InputHealth(p["stale_after_s"], p["fault_hold_s"], "chunks")
        self.stream_start_s = None       # wall time of sample 0 of the stream (from the chunks' stamps)
        self.recorder = None
        self.snapshot_problem = ""
        if p["snapshot_dir"] and p["max_snapshots"] > 0:
            try:
                os.makedirs(p["snapshot_dir"], exist_ok=True)
                if not os.access(p["snapshot_dir"], os.W_OK):
                    raise PermissionError(13, "not writable")
            except OSError as error:
                raise ParameterValueError(f"parameter 'snapshot_dir' = {p['snapshot_dir']!r}: "
                                          f"{error.strerror or error}; allowed: a folder this user can create and "
                                          "write (or '' for no snapshots)") from None
            topics = {self.resolve_topic_name(f"plant/{n}"): SIGNAL_CHUNK for n in self.signals}
            self.recorder = SnapshotRecorder(p["snapshot_dir"], p["drive_name"], self.reference.sample_period_s,
                                             p["snapshot_before_s"], p["snapshot_after_s"], topics,
                                             p["max_snapshots"])
        self.counts = {"chunks": 0, "events": 0, "evaluations": 0, "warnings": 0}
        # a1 against the motor speed, where the watch joins it (r: the configured drive-wheel radius, as analyze's)
        self.a1_chain = A1ChainCheck() if p["watch_omega1"] else None
        self.last_chunk_s: dict = {}     # per signal: monotonic time of its last chunk (a watched stream missing)
        qos = chunk_qos(p["qos"])
        self.fit_type = ModelFit
        self.topic_names = {n: self.resolve_topic_name(f"plant/{n}") for n in self.signals}
        for name in self.signals:
            self.create_subscription(SignalChunk, f"plant/{name}", lambda data, n=name: self.on_chunk(n, data), qos,
                                     raw=True)
        self.publisher = self.create_publisher(ModelFit, "model_fit", MODEL_FIT_QOS)
        self.diagnostics = DriveDiagnostics(self, "model fit", p["drive_name"], refresh=self.update_diagnostics)
        self.warn_text = ""
        self.get_logger().info(f"model {self.model}: {p['window_events']} onset events per evaluation, reference "
                               f"{self.reference.path}")

    # ------------------------------------------------------------------------------------------ stream
    def on_chunk(self, name: str, data: bytes) -> None:
        now = time.monotonic()
        self.health.arrived(now)
        self.last_chunk_s[name] = now
        try:
            fields = self.codec.signal_chunk_fields(memoryview(data), copy=False, strings=self.strings[name])
        except Exception:  # noqa: BLE001 - a malformed payload: counted, never raised into the executor
            fields = None
        if fields is None:
            self.faults.add("bad_message", f"plant/{name}: not a little-endian SignalChunk")
        else:
            sec, nanosec, frame_id, _sig, _unit, period, first, samples = fields
            if self.recorder is not None:
                self.recorder.add(self.topic_names[name], first, len(samples), time.time_ns(), data)
            if name in self.watched:
                joined = self.joiner.add(name, first, period, samples, (sec, nanosec), frame_id)
                if joined is not None:
                    self.process(joined)
        if self.health.update(now, self.faults):
            self.update_diagnostics(publish_now=True)

    def process(self, joined) -> None:
        arrays = joined.arrays
        n = len(arrays["a1"])
        if (abs(joined.sample_period_s - self.reference.sample_period_s) > 1e-9 * self.reference.sample_period_s
                or any(len(arrays[s]) != n for s in self.watched)
                or not all(math.isfinite(float(arrays[s].sum())) for s in self.watched)):
            self.faults.add("bad_range", f"range at sample {joined.first_sample_index}: sample period "
                            f"{joined.sample_period_s!r} (the model's {self.reference.sample_period_s:g} s), unequal "
                            "lengths or non-finite samples")
            self.watch.live.next_index = None       # the stream goes on after it: a gap for the events
            return
        self.counts["chunks"] += 1
        if self.a1_chain is not None:
            self.a1_chain.feed(joined.first_sample_index, arrays["a1"], arrays["omega1"], joined.sample_period_s,
                               finite=True)
        stamp_s = None if self.stream_start_s is not None else stamp_seconds(joined.stamp)
        if stamp_s is not None:
            self.stream_start_s = stream_origin_s(stamp_s, joined.first_sample_index, joined.sample_period_s)
        for update in self.watch.feed(joined.first_sample_index, arrays["a1"], arrays["a2"],
                                      arrays["angle_difference"], arrays.get("omega1")):
            self.on_update(update)

    # ------------------------------------------------------------------------------------------ results
    def stream_time(self, sample_index) -> float:
        if self.stream_start_s is None or sample_index is None:
            return time.time()
        return sample_time_s(self.stream_start_s, sample_index, self.reference.sample_period_s)

    def on_update(self, u) -> None:
        self.counts["evaluations"] += 1
        if u.changed and u.level == "WARN":
            self.counts["warnings"] += 1
            when = _dt.datetime.fromtimestamp(self.stream_time(u.since_sample_index), _dt.timezone.utc)
            if self.recorder is not None:
                snap = self.recorder.trigger(self.watch.live.ring.end, when)
                if snap is None:
                    self.snapshot_problem = ("no snapshot: " + ("one is still being recorded"
                                                                if self.recorder.pending is not None else
                                             f"max_snapshots = {self.params['max_snapshots']} written"))
                else:
                    self.snapshot_problem = ""
            self.get_logger().warning(self.message(u))
        self.publisher.publish(self.to_message(u))
        if u.changed:      # else the periodic publication's refresh (update_diagnostics) takes it up
            self.update_diagnostics(publish_now=True)

    def snapshot_text(self) -> str:
        if self.recorder is None or self.recorder.last is None:
            return ""
        s = self.recorder.last
        if s.state.startswith("failed"):
            return f"snapshot {s.path.name} not written ({s.error}): the evidence is only in the stream"
        if s.state == "recording":
            return f"snapshot {s.path.name} (recording the {self.params['snapshot_after_s']:g} s after)"
        return f"snapshot {s.path.name}"

    def message(self, u) -> str:
        r = u.evaluation.result
        ratio = r.residual_over_noise
        if u.level == "OK":
            return f"model {self.model} explains the drive (residual {ratio:.1f}x the noise floor)"
        since = _dt.datetime.fromtimestamp(self.stream_time(u.since_sample_index)).strftime("%H:%M:%S")
        phase, level = u.where
        parts = [f"model {self.model} no longer explains the drive since {since}: residual {ratio:.1f}x the noise "
                 "floor" + (f", in the {phase.replace('_', ' ')}, wavelet level {level}" if phase else "")]
        views = [v.replace("_", " ") for v in u.exceeding_views if v != "residual"]
        if views:
            parts[-1] += f" ({', '.join(views)} outside the band)"
        snap = self.snapshot_text()
        if snap:
            parts.append(snap + ("; run diagnose on it" if "not written" not in snap else ""))
        if self.snapshot_problem:
            parts.append(self.snapshot_problem)
        return "; ".join(parts)

    def to_message(self, u):
        ev = u.evaluation
        msg = self.fit_type()
        msg.header.stamp = time_from_seconds(self.stream_time(u.entry_sample_index))
        msg.header.frame_id = self.params["drive_name"]
        msg.level = msg.WARN if u.level == "WARN" else msg.OK
        msg.model = self.model
        msg.entry_sample_index = int(u.entry_sample_index)
        msg.events = int(u.events)
        msg.consistent = bool(ev.consistent)
        msg.exceeding = bool(u.exceeding)
        msg.signal_names = list(SEGMENT_SIGNALS)
        msg.residual_over_noise = to_float64_array([ev.residual_over_noise[s] for s in SEGMENT_SIGNALS])
        msg.residual_over_noise_overall = float(ev.result.residual_over_noise)
        names = list(ev.result.views)
        p = ev.p_values()
        msg.view_names = names
        msg.t2 = to_float64_array([ev.result.views[n].t2 for n in names])
        msg.t2_limit = to_float64_array([ev.result.views[n].limit for n in names])
        msg.t2_alarm = to_float64_array([u.limits.get(n, math.nan) for n in names])
        msg.p_value = to_float64_array([p[n] for n in names])
        msg.width_m = float(ev.width_m)
        msg.nominal_width_m = float(ev.nominal_width_m)
        phase, level = u.where
        msg.phase, msg.wavelet_level = phase, level
        msg.sensor_noise_psd = to_float64_array(ev.noise_psd)
        last = self.recorder.last if self.recorder is not None else None
        msg.snapshot = str(last.path) if last is not None else ""
        return msg

    def update_diagnostics(self, publish_now: bool = False) -> None:
        input_level, problem = self.health.state(time.monotonic())
        u = self.watch.last
        if u is None:
            n = len(self.watch.events)
            level, message = "OK", (f"model {self.model}: collecting onset events ({n} of "
                                    f"{self.watch.window_events})")
            values = {}
        else:
            level = u.level
            message = self.message(u)
            ev = u.evaluation
            values = {"residual_over_noise": f"{ev.result.residual_over_noise:.3f}",
                      "width_m": f"{ev.width_m:.5f}", "consistent": str(ev.consistent).lower(),
                      "p_min": f"{u.p_min:.3g}", "phase": u.where[0], "wavelet_level": u.where[1]}
            values.update({f"T2_{n}": f"{v.t2:.2f}" for n, v in ev.result.views.items()})
        if input_level == "STALE":
            level = "STALE" if level == "OK" else level
        elif input_level == "WARN" and level == "OK":
            level = "WARN"
        if self.a1_chain is not None:
            chain = self.a1_chain.result()
            values["a1_chain_mismatch"] = f"{chain.mismatch:.4f}"
            if chain.faulty:
                level = "WARN" if level == "OK" else level
                problem = "; ".join(x for x in (problem, f"{chain.text()}: the widths read from a1 and a1+a2 are not "
                                                "to be trusted (analyze takes a2's; docs/classifier.md 5.4)") if x)
        missing = self.missing_streams()
        if missing:
            level = "WARN" if level == "OK" else level
            problem = "; ".join(x for x in (problem, missing) if x)
        if problem:
            message = f"{message}; {problem}"
        self.diagnostics.set(level, message, publish_now=publish_now, model=self.model,
                             snapshot=self.snapshot_text(), input_faults=self.faults.summary(),
                             dropped_events=self.watch.live.dropped_events, **self.counts, **values)

    def missing_streams(self) -> str:
        """What is wrong when a watched stream is missing while the others come (each range waits for all of them,
        so the watch would evaluate nothing): the missing topics and what to do."""
        now, stale = time.monotonic(), self.params["stale_after_s"]
        if not any(now - t <= stale for t in self.last_chunk_s.values()):
            return ""                  # nothing comes at all: the input's STALE says it
        missing = [n for n in self.watched if now - self.last_chunk_s.get(n, -math.inf) > stale]
        if not missing:
            return ""
        text = f"no chunks on {', '.join(self.topic_names[n] for n in missing)} for {stale:g} s: no onset event is " \
               "evaluated"
        if missing == ["omega1"]:
            text += " (a drive without the motor speed: set watch_omega1 false)"
        return text

    def destroy_node(self):
        recorder = getattr(self, "recorder", None)
        if recorder is not None:
            recorder.flush()
        return super().destroy_node()


def main(args=None):
    return run_node(ModelWatchNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
