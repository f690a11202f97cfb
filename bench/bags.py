"""Bag (MCAP) record/read/analyze benchmark. Prints ONE JSON object (progress on stderr).

    python bench/bags.py [--seconds 3] [--factor 10]

(Named bags.py, not mcap.py: a bench/mcap.py would hide the `mcap` library from scripts here.)

- lost_messages: a publisher process streams SignalChunk messages (1000 samples = 20 ms at 50 kHz)
  on plant/a1, a2, omega1, omega2, angle_difference at `factor` x the nominal rate (10x = 2500
  messages/s, 2.5 M samples/s, ~20 MB/s) through real DDS (loopback, reliable, keep-last 100) into
  the record node in another process for `seconds`; published minus recorded.
- bytes_per_sample: bag size / samples, against 8 bytes of a float64 (zstd chunks; plant-like
  signals: a smooth waveform plus noise; white float64 noise does not compress).
- write_samples_per_s: BagWriter.write_raw of serialized chunks (the recorder's path);
  write_encode_samples_per_s includes our CDR encoding; container_write_vs_mcap_library: its speed
  over the `mcap` package's writer writing the same messages (zstd, 1 MiB chunks).
- read_samples_per_s: BagReader, every message decoded to numpy and each topic concatenated
  (read_signal).
- rosbags_read_samples_per_s: the same bag read and deserialized by rosbags (time_rosbags_read()).
- analyze_vs_rosbags_read: the whole `analyze` of a simulated 10 s bag against rosbags merely
  reading and deserializing the same topics of the same file (the four analyze reads; three before 30 Nov, stop 50): 15 rounds (ROUNDS), each an
  analyze run and a rosbags read of each layout back to back, which of the two goes first
  alternating from round to round, the garbage collector run before every timed run (either
  side's garbage is not collected inside the other's time); the figure is the median over the
  rounds of each pair's ratio (a load change hits both of a pair alike), ``..._fastest`` the
  ratio of each side's fastest run (the figure before: on a loaded machine the two fastest come
  from different moments, 0.53-2.4 in runs whose pair medians were 1.07-1.61); ``timing`` says so. Also on the bag rewritten by the `mcap` writer
  with rosbag2's writer options noSummary and noChunking (``..._noSummary``, ``..._noChunking``),
  and whether the three layouts gave the same estimates (``analyze_same_estimates_across_layouts``).
- container_*_vs_mcap_library: the container layer alone on the same bag (the topics' raw
  payloads; the SignalChunk fields analyze reads), backlash_monitor.bag's speed over the `mcap`
  package's reader (with our SignalChunk decoding on its payloads); > 1: ours is faster.
  damaged_*_read_fraction[_mcap_*]: the messages read back from that bag with a byte flipped in its
  middle chunk or cut in half, by our recovery and by the `mcap` package's readers. The measured
  reason docs/bags.md gives for not standing on the `mcap` package.

`time_rosbags_read(path)` and `time_project_read(path)` are importable for other benchmarks.
With `--role publish` this file is the publisher process of the DDS part (prints its own JSON).
"""
from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
for _extra in (REPO, REPO / "test"):   # test/: mcap_conformance's rewrite_with_mcap
    if str(_extra) not in sys.path:
        sys.path.insert(0, str(_extra))

from backlash_monitor.signals import SIGNAL_UNITS as UNITS  # noqa: E402
from backlash_monitor.signals import STREAM_SIGNALS as SIGNALS  # noqa: E402
CHUNK = 1000
FS = 50_000.0
SIGNAL_CHUNK = "backlash_monitor_msgs/msg/SignalChunk"


def plant_like(name: str, first: int, n: int, rng) -> np.ndarray:
    t = (first + np.arange(n)) / FS
    base = {"a1": 3.0 * np.sin(2 * np.pi * 4 * t), "a2": 0.5 * np.sin(2 * np.pi * 4 * t + 1),
            "omega1": 150 + 2 * np.sin(2 * np.pi * 4 * t), "omega2": 150 + 2 * np.sin(2 * np.pi * 4 * t),
            "angle_difference": 0.01 * np.sin(2 * np.pi * 4 * t)}[name]
    return base + 0.05 * rng.standard_normal(n)


def encoded_chunks(n_chunks: int, seed: int = 0):
    """[(topic, log_time_ns, cdr bytes, samples)] of a plant-like stream, in time order."""
    from backlash_monitor.bag import Codec

    codec = Codec.for_type(SIGNAL_CHUNK)
    rng = np.random.default_rng(seed)
    t0 = 1_763_000_000_000_000_000
    out = []
    for i in range(n_chunks):
        t = t0 + i * 20_000_000
        for name in SIGNALS:
            msg = codec.new(signal_name=name, unit=UNITS[name], sample_period_s=1 / FS,
                            first_sample_index=i * CHUNK, samples=plant_like(name, i * CHUNK, CHUNK, rng))
            msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(t, 1_000_000_000)
            msg.header.frame_id = "drive"
            out.append((f"/plant/{name}", t, codec.encode(msg), msg))
    return out


def time_write(path: Path, chunks, encode: bool = False) -> float:
    from backlash_monitor.bag import BagWriter

    start = time.perf_counter()
    with BagWriter(path) as w:
        for name in SIGNALS:
            w.add_topic(f"/plant/{name}", SIGNAL_CHUNK)
        if encode:
            for topic, t, _data, msg in chunks:
                w.write(topic, msg, log_time_ns=t)
        else:
            for topic, t, data, _msg in chunks:
                w.write_raw(topic, data, log_time_ns=t)
    return time.perf_counter() - start


def time_mcap_library_write(path: Path, chunks) -> float:
    """The same serialized messages written by the `mcap` package's writer (profile ros2, zstd
    chunks of 1 MiB as ours, its default indexes and summary; the schema text as ours)."""
    from mcap.writer import CompressionType, Writer

    from backlash_monitor.bag import full_definition

    start = time.perf_counter()
    with open(path, "wb") as f:
        w = Writer(f, chunk_size=1 << 20, compression=CompressionType.ZSTD)
        w.start("ros2", "bench")
        sid = w.register_schema(SIGNAL_CHUNK, "ros2msg", full_definition(SIGNAL_CHUNK).encode())
        cids = {f"/plant/{name}": w.register_channel(f"/plant/{name}", "cdr", sid)
                for name in SIGNALS}
        seq = dict.fromkeys(cids, 0)
        for topic, t, data, _msg in chunks:
            w.add_message(cids[topic], t, data, t, seq[topic])
            seq[topic] += 1
        w.finish()
    return time.perf_counter() - start


def time_project_read(path) -> tuple[int, float]:
    """(samples, seconds) for reading every SignalChunk topic of `path` into numpy arrays."""
    from backlash_monitor.bag import BagReader

    start = time.perf_counter()
    n = 0
    with BagReader(path) as bag:
        for series in bag.read_signals().values():
            n += series.samples.size
    return n, time.perf_counter() - start


def time_rosbags_read(path, topics=None) -> tuple[int, float]:
    """(samples, seconds) for reading and deserializing `path` with rosbags (AnyReader).

    Counts the samples of SignalChunk messages (float64[] `samples`); other messages are
    deserialized and counted as 0 samples. `topics`: restrict to these topics."""
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    start = time.perf_counter()
    n = 0
    with AnyReader([Path(path)], default_typestore=get_typestore(Stores.ROS2_JAZZY)) as reader:
        conns = [c for c in reader.connections if topics is None or c.topic in topics]
        for conn, _ts, raw in reader.messages(connections=conns):
            msg = reader.deserialize(raw, conn.msgtype)
            samples = getattr(msg, "samples", None)
            if samples is not None:
                n += len(samples)
    return n, time.perf_counter() - start


# ----------------------------------------------------------------------------------------------
# DDS part


def publisher_main(argv) -> int:
    """Child process: publish the 5 signal topics at `factor` x 50 kHz for `seconds`."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--role")
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--factor", type=float, default=10.0)
    ap.add_argument("--depth", type=int, default=100)
    ap.add_argument("--wait-subscribers", type=float, default=20.0)
    a = ap.parse_args(argv)
    import rclpy
    from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy

    from backlash_monitor.bag import Codec
    from backlash_monitor_msgs.msg import SignalChunk

    rclpy.init()
    node = rclpy.create_node("bench_bags_publisher")
    qos = QoSProfile(depth=a.depth, history=HistoryPolicy.KEEP_LAST,
                     reliability=ReliabilityPolicy.RELIABLE)
    pubs = {name: node.create_publisher(SignalChunk, f"plant/{name}", qos) for name in SIGNALS}
    deadline = time.monotonic() + a.wait_subscribers
    while time.monotonic() < deadline and not all(p.get_subscription_count() for p in pubs.values()):
        time.sleep(0.02)
    matched = all(p.get_subscription_count() for p in pubs.values())
    time.sleep(0.3)  # let the reliable readers finish matching both ways
    codec = Codec.for_type(SIGNAL_CHUNK)
    rng = np.random.default_rng(0)
    templates = {name: codec.new(signal_name=name, unit=UNITS[name], sample_period_s=1 / FS,
                                 samples=plant_like(name, 0, CHUNK, rng)) for name in SIGNALS}
    period = CHUNK / FS / a.factor
    n_chunks = int(round(a.seconds / period))
    sent = {name: 0 for name in SIGNALS}
    start = time.monotonic()
    for i in range(n_chunks):
        target = start + i * period
        now = time.monotonic()
        if target > now:
            time.sleep(target - now)
        stamp = time.time_ns()
        for name in SIGNALS:
            msg = templates[name]
            msg.first_sample_index = i * CHUNK
            msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(stamp, 1_000_000_000)
            pubs[name].publish(codec.encode(msg))
            sent[name] += 1
    elapsed = time.monotonic() - start
    from rclpy.duration import Duration

    acked = all(p.wait_for_all_acked(Duration(seconds=10)) for p in pubs.values())
    print(json.dumps({"published": {f"/plant/{k}": v for k, v in sent.items()},
                      "elapsed_s": elapsed, "matched": matched, "acked": acked}), flush=True)
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


def dds_record(out: Path, seconds: float, factor: float, env: dict) -> dict:
    rec = subprocess.Popen(
        [sys.executable, "-m", "backlash_monitor.nodes.record", "--ros-args",
         "-p", f"output:={out}", "-p", "topics:=plant/*", "-p", "queue_depth:=1000",
         "-p", "discovery_period_s:=0.05"],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=REPO)
    try:
        pub = subprocess.run([sys.executable, __file__, "--role", "publish", "--seconds", str(seconds),
                              "--factor", str(factor)], env=env, capture_output=True, text=True,
                             timeout=seconds * 4 + 60, cwd=REPO)
        if pub.returncode != 0:
            raise RuntimeError(f"publisher failed: {pub.stderr[-2000:]}")
        result = json.loads(pub.stdout.strip().splitlines()[-1])
        time.sleep(0.5)
    finally:
        rec.send_signal(signal.SIGINT)
        try:
            rec.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            rec.kill()
            rec.communicate()
    from backlash_monitor.bag import BagReader

    with BagReader(out) as bag:
        recorded = {t: i.count for t, i in bag.topics.items()}
    published = result["published"]
    lost = sum(max(0, n - recorded.get(t, 0)) for t, n in published.items())
    return {"published": sum(published.values()), "recorded": sum(recorded.values()),
            "lost": lost, "publish_elapsed_s": result["elapsed_s"], "acked": result["acked"]}


ROUNDS = 15  # analyze and rosbags timings, in alternated pairs; the fastest of each is reported
TIMING = (f"{ROUNDS} rounds; in each, per layout, one analyze run and one rosbags read back to back, "
          "which goes first alternating from round to round; gc.collect() before every timed run "
          "(outside its time); analyze_vs_rosbags_read = median over the rounds of rosbags read / "
          "analyze of the same round; _fastest = fastest rosbags read / fastest analyze; the wall "
          "times are each side's fastest")
LAYOUTS = {"default": None, "noSummary": {"noSummary": True}, "noChunking": {"noChunking": True}}
# the topics analyze reads: a1, a2, the angle difference and (since 30 Nov, stop 50: a1 checked against the motor
# speed, windowing/a1_chain.py) omega1; rosbags reads the same ones
ANALYZE_TOPICS = [f"/plant/{n}" for n in ("a1", "a2", "angle_difference", "omega1")]


def _analyze(analyze, parser, bag: Path, out: Path) -> float:
    """Seconds of one `analyze BAG --out OUT --no-model-fit` as the CLI runs it (its printout to stderr): the chain
    against reading the bag; the model fit (since 30 Nov on by default for one bag: ~3.5-6 s of CPU, and a reference
    built once) is not what this compares."""
    import contextlib

    args = parser.parse_args([str(bag), "--out", str(out), "--no-model-fit"])
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(sys.stderr):
        analyze.run(args)
    return time.perf_counter() - t0


def time_analyze(tmp: Path, seconds: float = 10.0) -> dict:
    """The whole offline analysis (`analyze`: read, join, window, denoise, classify, write) of a
    simulated bag against merely reading and decoding the same bag with rosbags, same run; on the
    project's layout and on the same recording rewritten by the `mcap` writer without a summary
    (rosbag2's noSummary) and without chunks (noChunking).

    `analyze.run` is what the CLI runs, settings included: it decompresses chunks in a worker
    thread when a core is free as it opens the bag (bag/prefetch.py: the load average says; else
    in its own; ``analyze_decompression_thread`` says which, at the start and the end of the timed
    rounds) and raises glibc's malloc thresholds for its process (process/memory.py). The
    rosbags read runs after it in this process, so under the same allocator setting (it takes
    fewer page faults too). Every analyze run writes its own output (the no-overwrite rule)."""
    import argparse as _argparse

    from mcap_conformance import rewrite_with_mcap

    from backlash_monitor.bag.simulated import write_simulation_bag
    from backlash_monitor.commands import analyze
    from backlash_monitor.plant import PlantSimulator, Scenario

    bags = {"default": tmp / "analyze.mcap"}
    write_simulation_bag(bags["default"], PlantSimulator([Scenario(width_m=0.0075, seed=11)],
                                                         outputs=SIGNALS), seconds)
    for name, options in LAYOUTS.items():
        if options:
            bags[name] = rewrite_with_mcap(bags["default"], tmp / f"analyze_{name}.mcap", **options)
    parser = _argparse.ArgumentParser()
    analyze.add_arguments(parser)
    estimates = {}
    for name, bag in bags.items():   # warm-up (imports, numba/pywt caches); the estimates
        _analyze(analyze, parser, bag, tmp / f"{name}_warmup")
        estimates[name] = (tmp / f"{name}_warmup.csv").read_text()
        time_rosbags_read(bag, ANALYZE_TOPICS)
    import gc
    import statistics

    def timed_analyze(name, bag, k):
        gc.collect()
        return _analyze(analyze, parser, bag, tmp / f"{name}_{k}")

    def timed_rosbags(bag):
        gc.collect()
        return time_rosbags_read(bag, ANALYZE_TOPICS)

    from backlash_monitor.bag.prefetch import default_chunks_ahead

    runs = {name: [] for name in bags}
    rosbags_runs = {name: [] for name in bags}
    load = [round(os.getloadavg()[0], 2)]
    thread = [default_chunks_ahead() > 0]
    for k in range(ROUNDS):         # alternated pairs: a load change hits both sides alike
        for name, bag in bags.items():
            if k % 2:
                rosbags_runs[name].append(timed_rosbags(bag))
                runs[name].append(timed_analyze(name, bag, k))
            else:
                runs[name].append(timed_analyze(name, bag, k))
                rosbags_runs[name].append(timed_rosbags(bag))
    load.append(round(os.getloadavg()[0], 2))
    thread.append(default_chunks_ahead() > 0)
    out = {"analyze_bag_seconds": seconds, "timing": TIMING,
           "load_average_1min_start_end": load, "analyze_decompression_thread_start_end": thread,
           "analyze_same_estimates_across_layouts": len(set(estimates.values())) == 1,
           "analyze_estimate_rows": estimates["default"].count("\n") - 1}
    for name in bags:
        t_analyze = min(runs[name])
        n_rb, t_rb = min(rosbags_runs[name], key=lambda x: x[1])
        suffix = "" if name == "default" else f"_{name}"
        out[f"analyze_vs_rosbags_read{suffix}"] = statistics.median(
            rb[1] / a for a, rb in zip(runs[name], rosbags_runs[name]))
        out[f"analyze_vs_rosbags_read{suffix}_fastest"] = t_rb / t_analyze
        out[f"analyze_wall_s{suffix}"] = t_analyze
        out[f"rosbags_read_same_topics_wall_s{suffix}"] = t_rb
        if name == "default":
            out["analyze_samples_per_s"] = n_rb / t_analyze
            out["analyze_samples"] = n_rb
    return out


def time_container(path: Path, rounds: int = ROUNDS) -> dict:
    """The container layer alone, on the bag analyze reads: the topics' raw payloads, and
    their SignalChunk fields (what analyze takes), by backlash_monitor.bag and by the `mcap`
    package's reader (make_reader: the summary's chunk index, file order) with the same
    SignalChunk decoding on its payloads. Interleaved rounds, the fastest of each."""
    from mcap.reader import make_reader

    from backlash_monitor.bag import BagReader, Codec

    codec = Codec.for_type(SIGNAL_CHUNK)

    def ours_raw():
        with BagReader(path) as bag:
            return sum(len(m.data) for m in bag.messages(ANALYZE_TOPICS, decode=False))

    def ours_fields():
        with BagReader(path) as bag:
            return sum(r.samples.size for r in bag.signal_chunks(ANALYZE_TOPICS))

    def mcap_raw():
        with open(path, "rb") as f:
            return sum(len(m.data) for _s, _c, m in
                       make_reader(f).iter_messages(ANALYZE_TOPICS, log_time_order=False))

    def mcap_fields():
        strings = {}
        n = 0
        with open(path, "rb") as f:
            for _s, channel, m in make_reader(f).iter_messages(ANALYZE_TOPICS,
                                                               log_time_order=False):
                fields = codec.signal_chunk_fields(memoryview(m.data), copy=False,
                                                   strings=strings.setdefault(channel.id, [None]))
                n += fields[-1].size
        return n

    sides = {"ours_raw": ours_raw, "mcap_raw": mcap_raw, "ours_fields": ours_fields,
             "mcap_fields": mcap_fields}
    best = {name: float("inf") for name in sides}
    results = {}
    for name, fn in sides.items():   # warm-up
        results[name] = fn()
    assert results["ours_raw"] == results["mcap_raw"], results
    assert results["ours_fields"] == results["mcap_fields"], results
    for _ in range(rounds):
        for name, fn in sides.items():
            t0 = time.perf_counter()
            fn()
            best[name] = min(best[name], time.perf_counter() - t0)
    return {"container_payload_bytes": results["ours_raw"],
            "container_raw_wall_s": best["ours_raw"],
            "container_raw_mcap_library_wall_s": best["mcap_raw"],
            "container_raw_vs_mcap_library": best["mcap_raw"] / best["ours_raw"],
            "container_signal_fields_wall_s": best["ours_fields"],
            "container_signal_fields_mcap_library_wall_s": best["mcap_fields"],
            "container_signal_fields_vs_mcap_library": best["mcap_fields"] / best["ours_fields"]}


def damaged_reads(path: Path, tmp: Path) -> dict:
    """Messages read back from the bag damaged as disks and killed writers damage it (one byte
    flipped in the middle chunk; the file cut in the middle), as a fraction of the intact bag's: by
    backlash_monitor.bag with recovery, and by the `mcap` package (its indexed reader, and its
    linear reader up to where it stops). The mcap package has no recovery: a reader raises at the
    first damaged record."""
    from mcap.reader import NonSeekingReader, make_reader

    import bag_damage
    from backlash_monitor.bag import BagReader

    data = path.read_bytes()
    with BagReader(path) as bag:
        total = bag.message_count
        middle = bag.chunks[len(bag.chunks) // 2]
    cases = {"flipped_byte": bag_damage.chunk_payload_byte(data, middle.offset, middle.length),
             "cut_in_half": bag_damage.truncate(data, len(data) // 2)}
    out = {}
    for name, damaged in cases.items():
        bad = tmp / f"damaged_{name}.mcap"
        bad.write_bytes(damaged)
        with BagReader(bad, recover=True) as bag:
            ours = sum(1 for _ in bag.messages(decode=False))
        got = {}
        for reader_name, make in (("mcap_indexed", lambda f: make_reader(f, validate_crcs=True)),
                                  ("mcap_linear", lambda f: NonSeekingReader(f, validate_crcs=True))):
            n = 0
            try:
                with open(bad, "rb") as f:
                    for _ in make(f).iter_messages(log_time_order=False):
                        n += 1
            except Exception:  # noqa: BLE001 - where it stops is the figure
                pass
            got[reader_name] = n
        out[f"damaged_{name}_read_fraction"] = ours / total
        for reader_name, n in got.items():
            out[f"damaged_{name}_read_fraction_{reader_name}"] = n / total
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seconds", type=float, default=3.0, help="DDS streaming time [s]")
    ap.add_argument("--factor", type=float, default=10.0, help="x the nominal rate")
    ap.add_argument("--chunks", type=int, default=500, help="chunk periods (20 ms) in the I/O bench")
    ap.add_argument("--role", default="bench", choices=("bench", "publish"))
    a, rest = ap.parse_known_args(argv)
    if a.role == "publish":
        return publisher_main(argv if argv is not None else sys.argv[1:])
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env.setdefault("ROS_DOMAIN_ID", "53")
    env["PYTHONPATH"] = str(REPO) + os.pathsep + env.get("PYTHONPATH", "")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        chunks = encoded_chunks(a.chunks)
        samples = len(chunks) * CHUNK
        t_raw = t_mcap_write = float("inf")
        for _ in range(2):   # interleaved, the fastest of each
            t_raw = min(t_raw, time_write(tmp / "w.mcap", chunks))
            t_mcap_write = min(t_mcap_write, time_mcap_library_write(tmp / "wm.mcap", chunks))
        t_enc = time_write(tmp / "we.mcap", chunks, encode=True)
        size = (tmp / "w.mcap").stat().st_size
        n_read, t_read = min((time_project_read(tmp / "w.mcap") for _ in range(2)), key=lambda x: x[1])
        n_rb, t_rb = time_rosbags_read(tmp / "w.mcap")
        assert n_read == n_rb == samples, (n_read, n_rb, samples)
        del chunks              # 2500 messages with their arrays: not scanned by the GC below
        import gc

        gc.collect()
        analysis = time_analyze(tmp)
        container = time_container(tmp / "analyze.mcap")
        container.update(damaged_reads(tmp / "analyze.mcap", tmp))
        try:
            dds = dds_record(tmp / "dds.mcap", a.seconds, a.factor, env)
        except Exception as exc:  # noqa: BLE001 - report, do not hide the I/O numbers
            dds = {"error": str(exc)}
    result = {
        "lost_messages": dds.get("lost"),
        "dds_published_messages": dds.get("published"),
        "dds_recorded_messages": dds.get("recorded"),
        "dds_rate_factor": a.factor,
        "dds_publish_elapsed_s": dds.get("publish_elapsed_s"),
        "bytes_per_sample": size / samples,
        "bytes_per_sample_float64": 8,
        "write_samples_per_s": samples / t_raw,
        "container_write_vs_mcap_library": t_mcap_write / t_raw,
        "write_encode_samples_per_s": samples / t_enc,
        "read_samples_per_s": n_read / t_read,
        "rosbags_read_samples_per_s": n_rb / t_rb,
        "realtime_samples_per_s": FS * len(SIGNALS),
        "io_bench_samples": samples,
        **analysis,
        **container,
    }
    if "error" in dds:
        result["dds_error"] = dds["error"]
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
