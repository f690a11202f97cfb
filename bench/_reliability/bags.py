"""Bad bags and bad command lines against `bag-info`, `analyze` and `replay`, run as a user runs
them (subprocesses). `run()` returns

    {"bad_inputs_tried": N, "escapes": M, "data_lost_bytes": B, "cases": [{"name", "outcome"}]}

- an input is one named bad bag (each tried with several commands) or one bad command line;
- an escape is a traceback, a crash (signal), a hang (timeout), an exit 0 that hides the damage or
  the bad input (a damaged bag read without --recover, a --recover result that does not report
  what was skipped, a refused input analysed anyway, a discard not counted) or a non-finite value in
  an estimate;
- data_lost_bytes: bytes of complete chunks (their contents intact in the damaged file, as the
  intact file has them; for the killed recorder: the chunks the `mcap` library reads with their
  CRCs) whose messages `--recover` did not give back.

Everything else goes to stderr; `python bench/_reliability/bags.py` prints the dict as JSON.
"""
from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
for _extra in (REPO, REPO / "test"):   # test/: bag_damage, the damage injected into the bags
    if str(_extra) not in sys.path:
        sys.path.insert(0, str(_extra))

TIMEOUT_S = 180
MIN_BYTES = 150_000       # the killed recorder's file: a few chunks (plant-like chunks compress ~12x)
DURATION_S = 3.0          # the simulated drive: 6 chunks of 0.5 s


def _log(*args) -> None:
    print("[bags]", *args, file=sys.stderr, flush=True)


def _env() -> dict:
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["ROS_DOMAIN_ID"] = str(int(env.get("ROS_DOMAIN_ID", "20")) + 7)
    env["PYTHONUNBUFFERED"] = "1"
    return env


class Runner:
    def __init__(self):
        self.env = _env()

    def __call__(self, *args, timeout=TIMEOUT_S):
        """(returncode or 'timeout', stdout, stderr) of `python -m backlash_monitor ARGS`."""
        try:
            proc = subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)],
                                  capture_output=True, text=True, timeout=timeout, env=self.env,
                                  cwd=REPO)
        except subprocess.TimeoutExpired as error:
            return "timeout", error.stdout or "", error.stderr or ""
        return proc.returncode, proc.stdout, proc.stderr


def _crash(rc, out, err) -> str | None:
    """The escape of a run that did not end with a clean exit code, if any."""
    if rc == "timeout":
        return "hang (timeout)"
    if rc < 0:
        return f"crash (signal {-rc})"
    if "Traceback" in out + err:
        return "traceback"
    return None


def _one_line_error(rc, err) -> bool:
    lines = [line for line in err.strip().splitlines() if line.strip()]
    return rc != 0 and 1 <= len(lines) <= 2


# ------------------------------------------------------------------ the bags

def _make_bags(directory: Path):
    """{name: (path, kind)}; kind: damaged (strict refuses, --recover reads), refused (always an
    error), counted (analysed, the bad part discarded and counted); and the intact source."""
    import numpy as np

    import bag_damage
    from backlash_monitor.bag.simulated import write_simulation_bag
    from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config

    intact = directory / "intact.mcap"
    sim = PlantSimulator([Scenario(0.0075, 0.025, 0.89, seed=11)], config=load_plant_config(), noise=True)
    write_simulation_bag(intact, sim, DURATION_S)
    data = intact.read_bytes()
    layout = bag_damage.chunk_layout(intact)
    off, length = layout[2][:2]
    bags = {}

    def put(name, content, kind):
        path = directory / f"{name}.mcap"
        path.write_bytes(content)
        bags[name] = (path, kind)

    put("truncated_inside_a_chunk", bag_damage.truncate(data, layout[3][0] + length // 3), "damaged")
    put("truncated_in_a_record_header", bag_damage.truncate(data, layout[3][0] + 5), "damaged")
    put("truncated_to_half", bag_damage.truncate(data, len(data) // 2), "damaged")
    put("chunk_length_too_long", bag_damage.chunk_length_field(data, off, 3 * length), "damaged")
    put("chunk_length_too_short", bag_damage.chunk_length_field(data, off, 100), "damaged")
    put("chunk_length_huge", bag_damage.chunk_length_field(data, off, 1 << 40), "damaged")
    put("chunk_crc_error", bag_damage.chunk_crc_field(data, off), "damaged")
    put("chunk_payload_byte", bag_damage.chunk_payload_byte(data, off, length), "damaged")
    put("two_damaged_chunks", bag_damage.chunk_crc_field(bag_damage.chunk_length_field(
        data, layout[1][0], 7), layout[4][0]), "damaged")
    put("missing_summary", bag_damage.without_summary(data), "damaged")
    put("summary_crc_error", bag_damage.summary_byte(data), "damaged")
    put("missing_summary_and_chunk_length",
        bag_damage.without_summary(bag_damage.chunk_length_field(data, off, 3 * length)), "damaged")
    header_gone = bytearray(bag_damage.without_summary(data))
    header_gone[off:off + 40] = b"\xee" * 40
    put("missing_summary_and_chunk_header", bytes(header_gone), "damaged")
    index_byte = bytearray(data)
    index_byte[off + length + 12] ^= 1
    put("message_index_byte", bytes(index_byte), "damaged")
    put("zero_length", b"", "refused")
    put("not_an_mcap", b"these are not the bytes of a bag\n" * 50, "refused")
    put("magic_only", data[:8], "refused")
    put("header_only", data[:layout[0][0]], "refused")

    def rewrite(name, change, kind):
        path = directory / f"{name}.mcap"
        bag_damage.rewrite_signals(intact, path, change)
        bags[name] = (path, kind)

    def slower(topic, f):
        f["sample_period_s"] = 4e-5
        return f

    def faster(topic, f):
        f["sample_period_s"] = 1e-5
        return f

    def swapped(topic, f):
        if topic.endswith("/a1"):
            f["signal_name"], f["unit"] = "a2", "m/s^2"
        return f

    def unit(topic, f):
        if topic.endswith("/a1"):
            f["unit"] = "g"
        return f

    def no_a2(topic, f):
        return None if topic.endswith("/a2") else f

    def short_a2(topic, f):
        if topic.endswith("/a2") and f["first_sample_index"] in (20_000, 90_000):
            f["samples"] = f["samples"][:700]
        return f

    def nan_period(topic, f):
        if f["first_sample_index"] == 30_000:
            f["sample_period_s"] = float("nan")
        return f

    def negative_period(topic, f):
        f["sample_period_s"] = -2e-5
        return f

    def nan_samples(topic, f):
        if topic.endswith("/a1") and f["first_sample_index"] in (3_000, 40_000):
            f["samples"] = np.full_like(f["samples"], np.nan)
        return f

    rewrite("sample_rate_25kHz", slower, "refused")
    rewrite("sample_rate_100kHz", faster, "refused")
    rewrite("a1_topic_carries_a2", swapped, "refused")
    rewrite("a1_in_another_unit", unit, "refused")
    rewrite("missing_a2_topic", no_a2, "refused")
    rewrite("every_period_negative", negative_period, "refused")
    rewrite("a1_a2_chunk_lengths_differ", short_a2, "counted")
    rewrite("nan_sample_period_in_one_range", nan_period, "counted")
    rewrite("nan_samples_in_a1", nan_samples, "counted")
    return intact, bags


def _chunk_keys(path, layout):
    """Per chunk of the intact layout: the (topic, log_time, sequence) of the messages in it
    (its records decompressed: chunks may share a boundary log time)."""
    from backlash_monitor.bag import BagReader
    from backlash_monitor.bag.records import MESSAGE_HEAD, chunk_records, message_bodies

    data = Path(path).read_bytes()
    with BagReader(path) as bag:
        topics = {t.channel_id: t.name for t in bag.topics.values()}
    out = []
    for off, length, *_ in layout:
        keys = set()
        for rbody in message_bodies(chunk_records(memoryview(data)[off + 9:off + length])):
            cid, seq, log_time, _pub = MESSAGE_HEAD.unpack_from(rbody, 0)
            keys.add((topics[cid], log_time, seq))
        out.append(keys)
    return out


def _lost_bytes(intact_data, layout, per_chunk, damaged_path) -> int:
    """Bytes of the chunks whose contents are intact in the damaged file but not recovered."""
    from backlash_monitor.bag import BagReader
    from backlash_monitor.bag.errors import BagError

    damaged = damaged_path.read_bytes()
    try:
        with BagReader(damaged_path, recover=True) as bag:
            got = {(m.topic, m.log_time_ns, m.sequence) for m in bag.messages(decode=False)}
    except (BagError, OSError):
        got = set()
    lost = 0
    for (off, length, _s, _e), keys in zip(layout, per_chunk):
        complete = (off + length <= len(damaged)
                    and damaged[off + 9:off + length] == intact_data[off + 9:off + length])
        if complete and not keys <= got:
            lost += length
    return lost


# ------------------------------------------------------------------ checks per command

def _analysis(out_prefix: Path):
    path = Path(f"{out_prefix}.json")
    if not path.is_file():
        return None
    return json.loads(path.read_text())


def _finite_estimates(result) -> bool:
    for row in result.get("estimates", []):
        values = [row["width_m"], row["b_margin"], *row["b_vector"]]
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            return False
    return True


def _try_bag(run, name, path, kind, work: Path, replay: bool) -> list[tuple[str, str]]:
    """[(escape or '', outcome text)] of every command tried on one bag."""
    results = []

    def note(tool, rc, out, err, escape=None):
        escape = _crash(rc, out, err) or escape
        first = (err.strip().splitlines() or [""])[0][:160]
        results.append((escape or "", f"{tool}: exit {rc}" + (f" ({first})" if first else "")
                        + (f" ESCAPE: {escape}" if escape else "")))

    rc, out, err = run("bag-info", path)
    note("bag-info", rc, out, err, None if rc != 0 and _one_line_error(rc, err) else
         "exit 0 on a damaged bag" if rc == 0 and kind == "damaged" else None)
    if kind == "damaged":
        rc, out, err = run("bag-info", path, "--recover", "--format", "json")
        escape = None
        if rc == 0:
            info = json.loads(out)
            if info["recovery"]["intact"]:
                escape = "--recover says intact"
        note("bag-info --recover", rc, out, err, escape)
    prefix = work / f"{name}.analysis"
    rc, out, err = run("analyze", path, "--out", prefix, "--overwrite")
    escape = None
    if rc == 0:
        result = _analysis(prefix)
        if kind in ("damaged", "refused"):
            escape = "analysed without --recover / a refused input analysed"
        elif kind == "counted" and not (result and sum(result["input_faults"].values())
                                        + len(result["discarded_windows"]) > 0
                                        or "discard" in out):
            escape = "bad chunks neither refused nor counted"
        if result is not None and not _finite_estimates(result):
            escape = "non-finite estimate"
    elif not _one_line_error(rc, err):
        escape = escape or ("no clear one-line error" if _crash(rc, out, err) is None else None)
    note("analyze", rc, out, err, escape)
    if kind == "damaged":
        rc, out, err = run("analyze", path, "--out", prefix, "--overwrite", "--recover")
        escape = None
        if rc == 0:
            result = _analysis(prefix)
            integrity = (result or {}).get("bag_integrity") or {}
            if integrity.get("intact", True):
                escape = "--recover result does not report the damage"
            if result is not None and not _finite_estimates(result):
                escape = "non-finite estimate"
        elif not _one_line_error(rc, err):
            escape = "no clear one-line error"
        note("analyze --recover", rc, out, err, escape)
    if replay:
        rc, out, err = run("replay", path, "--rate-factor", "1000", timeout=60)
        note("replay", rc, out, err, "played a damaged bag without a word"
             if rc == 0 and kind == "damaged" and "DAMAGED" not in err + out else None)
    return results


COMMAND_LINES = [
    ("bag-info without a bag", ["bag-info"]),
    ("bag-info of a missing file", ["bag-info", "{missing}"]),
    ("bag-info --topic not in the bag", ["bag-info", "{intact}", "--topic", "/nope"]),
    ("bag-info of a directory", ["bag-info", "{dir}"]),
    ("analyze of a missing file", ["analyze", "{missing}"]),
    ("analyze --fusion-events 0", ["analyze", "{intact}", "--fusion-events", "0", "--out", "{out}"]),
    ("analyze --library missing", ["analyze", "{intact}", "--library", "/nonexistent/lib.npz",
                                   "--out", "{out}"]),
    ("analyze --library not an npz", ["analyze", "{intact}", "--library", "{intact}",
                                      "--out", "{out}"]),
    ("analyze --window-offset -1", ["analyze", "{intact}", "--window-offset", "-1", "--out", "{out}"]),
    ("analyze --namespace without topics", ["analyze", "{intact}", "--namespace", "/line9",
                                            "--out", "{out}"]),
    ("analyze --out onto its input", ["analyze", "{intact}", "--out", "{intact_prefix}",
                                      "--overwrite"]),
    ("analyze --trigger paper without width", ["analyze", "{intact}", "--trigger", "paper",
                                               "--out", "{out}"]),
    ("analyze --mode unknown", ["analyze", "{intact}", "--mode", "magic", "--out", "{out}"]),
    ("analyze --n1 without patterns", ["analyze", "{intact}", "--mode", "paper", "--n1", "0.5",
                                       "--out", "{out}"]),
    ("replay without a bag", ["replay"]),
    ("replay --rate-factor -1", ["replay", "{intact}", "--rate-factor", "-1"]),
    ("replay --topics not in the bag", ["replay", "{intact}", "--topics", "/nope"]),
    ("replay of a missing file", ["replay", "{missing}"]),
]


def _try_command_line(run, args) -> tuple[str, str]:
    rc, out, err = run(*args, timeout=60)
    escape = _crash(rc, out, err)
    if escape is None and rc == 0:
        escape = "exit 0 on a bad command line"
    if escape is None and not (err.strip() or out.strip()):
        escape = "no message"
    first = (err.strip().splitlines() or [""])[-1][:160]
    return escape or "", f"exit {rc} ({first})" + (f" ESCAPE: {escape}" if escape else "")


# ------------------------------------------------------------------ the killed recorder

def _killed_recorder(run, work: Path) -> tuple[str, str, int]:
    """A real SIGKILL of `record` while a publisher streams: (escape, outcome, lost bytes)."""
    env = run.env
    out = work / "killed.mcap"
    rec = subprocess.Popen([sys.executable, "-m", "backlash_monitor", "record", "--output", str(out),
                            "--topics", "plant/*", "--chunk-duration-s", "0.25"],
                           env=env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    pub = subprocess.Popen([sys.executable, str(REPO / "bench" / "bags.py"), "--role", "publish",
                            "--seconds", "6", "--factor", "1"], env=env, cwd=REPO,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and (not out.exists() or out.stat().st_size < MIN_BYTES):
            time.sleep(0.05)
        time.sleep(0.6)    # into the stream: chunks closed, one open
        killed_ns = time.time_ns()
        rec.send_signal(signal.SIGKILL)
        rec.wait(timeout=10)
    finally:
        for proc in (rec, pub):
            if proc.poll() is None:
                proc.kill()
            proc.wait(timeout=30)
    if not out.exists() or out.stat().st_size < MIN_BYTES:
        return "", "recorder did not record (publisher not matched): not tried", 0
    rc, o, e = run("bag-info", out)
    escape = _crash(rc, o, e) or (None if rc == 1 and "--recover" in e else "killed bag not refused")
    rc, o, e = run("bag-info", out, "--recover", "--format", "json")
    escape = escape or _crash(rc, o, e)
    lost_s = None
    if rc == 0:
        rep = json.loads(o)["recovery"]
        if not rep["open_chunk"]:
            escape = escape or "--recover does not say how much time the open chunk held"
        lost_s = (killed_ns - rep["last_message_ns"]) / 1e9 if rep["last_message_ns"] else None
    # the complete chunks as the mcap library sees them (CRC-checked), against what we recovered
    from mcap.stream_reader import StreamReader

    from backlash_monitor.bag import BagReader

    import zlib

    import zstandard

    complete = []
    with open(out, "rb") as f:
        try:
            for record in StreamReader(f, emit_chunks=True).records:
                if type(record).__name__ != "Chunk":
                    continue
                data = (zstandard.ZstdDecompressor().decompress(
                    record.data, max_output_size=record.uncompressed_size)
                        if record.compression == "zstd" else record.data)
                if not record.uncompressed_crc or zlib.crc32(data) == record.uncompressed_crc:
                    complete.append(record)
        except Exception:  # noqa: BLE001 - the cut end of the file
            pass
    with BagReader(out, recover=True) as bag:
        recovered = bag.recovery.complete_chunks
        starts = sorted(c.start for c in bag.chunks)
    lost = 0
    for chunk in complete:
        if chunk.message_start_time not in starts:
            lost += len(chunk.data)
    outcome = (f"SIGKILL: {len(complete)} complete chunks (mcap library), {recovered} recovered; "
               f"{lost_s:.3f} s between the last recovered message and the kill (chunk 0.25 s)"
               if lost_s is not None else f"bag-info --recover exit {rc}")
    if lost_s is not None and lost_s > 0.25 + 0.35:
        escape = escape or f"lost {lost_s:.2f} s, more than the open chunk"
    return escape or "", outcome + (f" ESCAPE: {escape}" if escape else ""), lost


# ------------------------------------------------------------------ run

def run(replay_all: bool = True) -> dict:
    run_ = Runner()
    cases = []
    escapes = 0
    lost_total = 0
    with tempfile.TemporaryDirectory(prefix="bags_reliability_") as tmp:
        work = Path(tmp)
        intact, bags = _make_bags(work)
        intact_data = intact.read_bytes()
        import bag_damage

        layout = bag_damage.chunk_layout(intact)
        per_chunk = _chunk_keys(intact, layout)
        # control: the intact bag passes every command (not counted as a bad input)
        rc, out, err = run_("analyze", intact, "--out", work / "intact.analysis")
        _log("control analyze of the intact bag: exit", rc, err.strip()[-200:])
        for name, (path, kind) in bags.items():
            results = _try_bag(run_, name, path, kind, work, replay_all or kind == "damaged")
            lost = _lost_bytes(intact_data, layout, per_chunk, path) if kind == "damaged" else 0
            lost_total += lost
            bad = [e for e, _ in results if e]
            escapes += bool(bad)
            outcome = "; ".join(text for _, text in results) + (f"; lost {lost} bytes" if lost else "")
            cases.append({"name": f"bag: {name}", "outcome": outcome, "escape": bool(bad)})
            _log(name, "ESCAPE" if bad else "ok", lost)
        two = work / "two"
        two.mkdir()
        for i in (1, 2):
            (two / f"{i}.mcap").write_bytes(intact_data)
        subs = {"{missing}": str(work / "missing.mcap"), "{intact}": str(intact), "{dir}": str(two),
                "{out}": str(work / "cl"), "{intact_prefix}": str(intact.with_suffix(""))}
        for name, args in COMMAND_LINES:
            escape, outcome = _try_command_line(run_, [subs.get(a, a) for a in args])
            escapes += bool(escape)
            cases.append({"name": f"command line: {name}", "outcome": outcome, "escape": bool(escape)})
            _log(name, "ESCAPE" if escape else "ok")
        escape, outcome, lost = _killed_recorder(run_, work)
        lost_total += lost
        escapes += bool(escape)
        cases.append({"name": "bag: recorder killed with SIGKILL", "outcome": outcome,
                      "escape": bool(escape)})
        _log("killed recorder", outcome)
    return {"bad_inputs_tried": len(cases), "escapes": escapes, "data_lost_bytes": lost_total,
            "cases": cases}


if __name__ == "__main__":
    print(json.dumps(run(), indent=1))
