"""The new entry detector against the frozen old one (reference_detector.py) on every scenario of
scenarios.py: entries (all fields), event logs, re-reference counts and the bits of the state's
floats after every feed. Prints one JSON object (counts, and the first differences if any).

    python bench/_detector/identity.py [--quick] [--save FILE] [--against FILE]

--save FILE: also store the new detector's results (pickle); --against FILE: compare with such a
file instead of running the old detector (e.g. results saved before a change).
"""
from __future__ import annotations

import argparse
import json
import os
import pickle
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(HERE, "..", "..")]

import reference_detector  # noqa: E402
import scenarios  # noqa: E402
from backlash_monitor.windowing import BacklashEntryDetector  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="fewer records and chunkings")
    ap.add_argument("--save")
    ap.add_argument("--against")
    ap.add_argument("--seconds", type=float, default=10.0)
    a = ap.parse_args(argv)
    t0 = time.time()
    combos = scenarios.ETA_N1_SEED[:1] if a.quick else scenarios.ETA_N1_SEED
    records = scenarios.plant_records(a.seconds, combos=combos)
    print(f"simulated {len(records)} records in {time.time() - t0:.1f} s", file=sys.stderr)
    scen = scenarios.plant_scenarios(records, quick=a.quick) + scenarios.synthetic_scenarios()
    if not a.quick:
        scen += scenarios.chunk_one_scenarios(records)
    old = pickle.load(open(a.against, "rb")) if a.against else None
    new_all, diffs, n_entries, n_feeds = {}, [], 0, 0
    for k, sc in enumerate(scen):
        name = sc[0]
        new = scenarios.run(BacklashEntryDetector, sc)
        ref = old[name] if old is not None else scenarios.run(reference_detector.BacklashEntryDetector, sc)
        new_all[name] = new
        n_entries += len(new["entries"])
        n_feeds += len(sc[2])
        for key in ("entries", "events", "n_rereferences", "states"):
            if new[key] != ref[key]:
                diffs.append({"scenario": name, "field": key})
                break
        if k % 50 == 0:
            print(f"{k}/{len(scen)} {name} {time.time() - t0:.0f} s", file=sys.stderr)
    if a.save:
        with open(a.save, "wb") as fh:
            pickle.dump(new_all, fh)
    print(json.dumps({"scenarios": len(scen), "feeds": n_feeds, "entries": n_entries,
                      "identical_scenarios": len(scen) - len(diffs), "differences": diffs[:20],
                      "against": a.against or "reference_detector.py", "seconds": round(time.time() - t0, 1)}))
    return 0 if not diffs else 1


if __name__ == "__main__":
    sys.exit(main())
