#!/usr/bin/env bash
# The model watch in one command (README, docs/model_watch.md): a simulated 5 mm drive runs on its model; at 30 s
# 1.5 N*m of dry friction appears in its load wheel's bearing; the watch goes WARN and writes a snapshot bag;
# diagnose names the effect on the snapshot; add-effect and train --model make the next model version (with its
# watch reference); the same drive, friction and all, reads OK on the new version.
#
#     bash docs/examples/model_watch_demo.sh [DIR]        # DIR: a new folder (default watch_demo); ~4 min
set -euo pipefail
DIR="${1:-watch_demo}"
if [ -e "$DIR" ] && [ -n "$(ls -A "$DIR" 2>/dev/null)" ]; then
    echo "model_watch_demo: $DIR exists and is not empty; give a new folder (nothing is overwritten)" >&2
    exit 2
fi
mkdir -p "$DIR"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST                  # DDS stays on this machine
export ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-$(( ($$ % 100) + 1 ))}"
FRICTION=(effects.wheel_coulomb_friction=true wheel_coulomb_friction.torque_Nm=1.5)
bm() { python -m backlash_monitor "$@"; }
step() { printf '\n=== %s\n' "$*"; }

step "1. the drive on its model (default v1 at 5 mm); friction from t = 30 s"
bm pipeline --watch --width-m 0.005 --duration 45 --rate-factor 3 --snapshot-dir "$DIR" \
    --set-at 30s "${FRICTION[@]}" | tee "$DIR/run_v1.txt" | grep -E "^pipeline|^t=  *(2[89]|3[0-9])\." || true
SNAPSHOT="$(ls "$DIR"/drive_*.mcap | head -n 1)"
echo "snapshot: $SNAPSHOT"

step "2. diagnose the snapshot"
bm diagnose "$SNAPSHOT" --width-m 0.005 --json "$DIR/diag.json" | tail -n 3

step "3. the next model version, and its monitor and watch reference"
bm add-effect "$DIR/diag.json" -o "$DIR/drive_v2.yaml"
bm train --model "$DIR/drive_v2.yaml" -o "$DIR/lib_v2.npz" --seeds 1000,1001 --no-progress

step "4. the same drive (friction on) on the new version"
bm pipeline --watch --model "$DIR/drive_v2.yaml" --library "$DIR/lib_v2.npz" --width-m 0.005 --duration 24 \
    --rate-factor 3 --snapshot-dir "$DIR/v2" --set "${FRICTION[0]}" --set "${FRICTION[1]}" \
    | tee "$DIR/run_v2.txt" | tail -n 4
