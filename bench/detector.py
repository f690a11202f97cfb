"""Entry detector speed: the detector now against its frozen old version, side by side. ONE JSON object.

    python bench/detector.py [--rounds 7]

Records: the plant simulator, noise on, widths 2.5 / 5 / 10 mm (eta_k 0.025, n1 0.93, seed 0), 10 s
each and their first 4 s. Cases (per record, ms of CPU per record, the fastest of ``rounds``
interleaved rounds per side, old and new alternating which goes first):
- ``whole_*``: one feed of the whole record, trigger contact_loss, as workbench/events.py
  ``onset_entries`` does (``diagnose`` calls it ~660 times per diagnosis); measured angle difference
  and integrated speeds;
- ``chunk1000_*``: 1000-sample chunks (20 ms at 50 kHz), as the live windowing node gets them;
  contact_loss and paper (integrated speeds);
- ``block65536``: blocks of 65 536 samples, as ``analyze`` feeds measured angles (chain.block_feeder.BlockFeeder).
``speedup_*`` = old time / new time (> 1: the new one is faster). ``identical``: every case gave
the same entries (all fields) from both. The old version is bench/_detector/reference_detector.py;
the full identity check over ~1150 scenarios is bench/_detector/identity.py.

``analyze_*``: the whole ``analyze`` of bench/bags.py's simulated 10 s bag (7.5 mm, seed 11; the
project's layout), run as the CLI runs it with the detector now and with the old one patched into
the chain, and rosbags merely reading the same three topics (bags.py's yardstick for issue 17):
``rounds`` interleaved rounds, the fastest of each; ``analyze_vs_rosbags_read_{old,new}_detector``
and whether both gave the same CSV. ``--no-analyze`` leaves it out.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(HERE, "_detector"), HERE, os.path.join(HERE, "..")]

import reference_detector  # noqa: E402
import scenarios  # noqa: E402
from backlash_monitor.windowing import BacklashEntryDetector  # noqa: E402

WIDTHS = (0.0025, 0.005, 0.01)
DT = 2e-5


def cases(records):
    """{case: (detector kwargs, [feeds per record])}."""
    out = {}
    for secs in (4, 10):
        n = int(secs / DT)
        rec = [{k: v[:n] for k, v in sig.items()} for _, _, sig in records]
        out[f"whole_measured_{secs}s"] = ({"trigger": "contact_loss"},
                                          [[(0, scenarios.measured(s), DT)] for s in rec])
        out[f"whole_integrated_{secs}s"] = ({"trigger": "contact_loss", "angle_source": "integrated"},
                                            [[(0, scenarios.speeds(s), DT)] for s in rec])
        if secs == 10:
            out["chunk1000_measured_10s"] = ({"trigger": "contact_loss"},
                                             [scenarios.chunked(scenarios.measured(s), 1000, period=DT) for s in rec])
            out["chunk1000_integrated_10s"] = ({"trigger": "contact_loss"},
                                               [scenarios.chunked(scenarios.speeds(s), 1000, period=DT) for s in rec])
            out["block65536_measured_10s"] = ({"trigger": "contact_loss"},
                                              [scenarios.chunked(scenarios.measured(s), 65536, period=DT) for s in rec])
    return out


def run_case(cls, kw, feeds_per_record, widths):
    got = []
    for feeds, width in zip(feeds_per_record, widths):
        det = cls(**dict(kw, width_m=width) if kw.get("trigger") == "paper" else kw)
        for first, sig, period in feeds:
            got += [(e.sample_index, e.kind, e.trigger, e.confirm_sample_index) for e in det.feed(first, sig, period)]
    return got


def analyze_old_vs_new(rounds: int) -> dict:
    """analyze of a 10 s bag with the new and the old detector, and rosbags reading it (see above)."""
    import backlash_monitor.chain.stage as stage   # WindowingStage looks BacklashEntryDetector up there
    import bags
    from backlash_monitor.bag.simulated import write_simulation_bag
    from backlash_monitor.commands import analyze
    from backlash_monitor.plant import PlantSimulator, Scenario

    detectors = {"new": stage.BacklashEntryDetector, "old": reference_detector.BacklashEntryDetector}
    parser = argparse.ArgumentParser()
    analyze.add_arguments(parser)
    best = {"new": float("inf"), "old": float("inf"), "rosbags": float("inf")}
    csv = {}
    with tempfile.TemporaryDirectory() as tmp:
        bag = Path(tmp) / "analyze.mcap"
        write_simulation_bag(bag, PlantSimulator([Scenario(width_m=0.0075, seed=11)],
                                                 outputs=bags.SIGNALS), 10.0)
        try:
            for k in range(-1, rounds):          # round -1: warm-up (imports, caches), not timed
                for side in (("new", "old") if k % 2 == 0 else ("old", "new")):
                    stage.BacklashEntryDetector = detectors[side]
                    out = Path(tmp) / f"{side}_{k}"
                    t = bags._analyze(analyze, parser, bag, out)
                    csv[side] = (Path(tmp) / f"{side}_{k}.csv").read_text()
                    if k >= 0:
                        best[side] = min(best[side], t)
                t = bags.time_rosbags_read(bag, bags.ANALYZE_TOPICS)[1]
                if k >= 0:
                    best["rosbags"] = min(best["rosbags"], t)
        finally:
            stage.BacklashEntryDetector = detectors["new"]
    return {"analyze_new_detector_ms": round(best["new"] * 1e3, 1),
            "analyze_old_detector_ms": round(best["old"] * 1e3, 1),
            "rosbags_read_same_topics_ms": round(best["rosbags"] * 1e3, 1),
            "analyze_vs_rosbags_read_new_detector": round(best["rosbags"] / best["new"], 3),
            "analyze_vs_rosbags_read_old_detector": round(best["rosbags"] / best["old"], 3),
            "analyze_same_csv_old_new_detector": csv["new"] == csv["old"]}


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--no-analyze", action="store_true")
    a = ap.parse_args(argv)
    t0 = time.time()
    records = scenarios.plant_records(10.0, widths=WIDTHS, combos=((0.025, 0.93, 0),))
    print(f"simulated {len(records)} records in {time.time() - t0:.1f} s", file=sys.stderr)
    widths = [w for _, w, _ in records]
    cs = cases(records)
    cs["chunk1000_paper_integrated_10s"] = ({"trigger": "paper"}, cs["chunk1000_integrated_10s"][1])
    result = {"records": len(records), "widths_mm": [w * 1e3 for w in widths], "rounds": a.rounds}
    identical = True
    sides = {"old": reference_detector.BacklashEntryDetector, "new": BacklashEntryDetector}
    for name, (kw, feeds) in cs.items():
        best = {"old": float("inf"), "new": float("inf")}
        out = {}
        for r in range(a.rounds):
            for side in (("old", "new") if r % 2 == 0 else ("new", "old")):
                t = time.process_time()
                out[side] = run_case(sides[side], kw, feeds, widths)
                best[side] = min(best[side], time.process_time() - t)
        identical &= out["old"] == out["new"]
        per = len(records)
        result[f"{name}_old_ms"] = round(best["old"] / per * 1e3, 2)
        result[f"{name}_new_ms"] = round(best["new"] / per * 1e3, 2)
        result[f"speedup_{name}"] = round(best["old"] / best["new"], 2)
        print(f"{name}: old {best['old'] / per * 1e3:.2f} ms, new {best['new'] / per * 1e3:.2f} ms per record, "
              f"{len(out['new'])} entries", file=sys.stderr)
    result["identical"] = identical
    if not a.no_analyze:
        result.update(analyze_old_vs_new(a.rounds))
    result["load_average"] = [round(x, 2) for x in os.getloadavg()]
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
