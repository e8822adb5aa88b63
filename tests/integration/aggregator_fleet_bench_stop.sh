#!/usr/bin/env bash
# litamin2-fleet-bench stopped before its target (nothing timed: the bounds only make it stop):
#  1. --max-wall-s: the feeding stops, the run finishes as at the end (queue ingested, store
#     reopened, graph recovered identical) and the JSON is valid with the keyframes reached
#     (fewer than the target), "stopped_early": true and the reason;
#  2. SIGTERM mid-run does the same and the bench exits 0;
#  3. a negative --max-wall-s is refused.
# Usage: aggregator_fleet_bench_stop.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1
work=$2
bench=$build/tools/bench/litamin2-fleet-bench
rm -rf "$work"
mkdir -p "$work"
cd "$work"
target=10000000

# check JSON REASON: valid JSON of a run stopped early for REASON, restart identical.
check() {
  python3 - "$1" "$2" "$target" <<'PY'
import json, sys
path, reason, target = sys.argv[1], sys.argv[2], int(sys.argv[3])
with open(path) as f:
    s = json.load(f)
errors = []
if s["stopped_early"] is not True: errors.append("stopped_early is not true")
if s["stop_reason"] != reason: errors.append(f"stop_reason {s['stop_reason']!r}, not {reason!r}")
if s["target_keyframes"] != target: errors.append(f"target_keyframes {s['target_keyframes']}")
if not 0 < s["keyframes"] < target: errors.append(f"keyframes {s['keyframes']} not in (0, target)")
if s["restart_identical"] is not True: errors.append("restart differs")
if s["keyframes_in_map_frame"] <= 0: errors.append("no keyframe in the map frame")
if len(s["mapping_cpu_ms_per_keyframe_10k_windows"]) != s["keyframes"] // 10000:
    errors.append("10k windows do not cover the keyframes reached")
if errors:
    sys.exit(path + ": " + "; ".join(errors))
print(f"ok: {path}: {s['keyframes']} of {target} keyframes ({reason})")
PY
}

echo "== 1: --max-wall-s 3"
"$bench" --vehicles 10 --keyframes $target --search-spacing 200 --max-wall-s 3 \
  --store wall.db --json wall.json > wall.out 2> wall.log || { cat wall.log; exit 1; }
cat wall.log
check wall.json max_wall_s
cmp wall.json wall.out  # the same summary on stdout

echo "== 2: SIGTERM"
"$bench" --vehicles 10 --keyframes $target --search-spacing 200 --store term.db \
  --json term.json > term.out 2> term.log &
pid=$!
# The store exists once the bench has blocked the signals and opened its core.
for _ in $(seq 1 100); do [ -e term.db ] && break; sleep 0.1; done
[ -e term.db ] || { kill -9 $pid; cat term.log; echo "no store after 10 s"; exit 1; }
sleep 1
kill -TERM $pid
rc=0
wait $pid || rc=$?
cat term.log
[ $rc -eq 0 ] || { echo "exit status $rc after SIGTERM"; exit 1; }
check term.json SIGTERM

echo "== 3: a negative bound is refused"
if "$bench" --keyframes 10 --max-wall-s -1 --store bad.db > bad.out 2>&1; then
  echo "--max-wall-s -1 accepted"
  exit 1
fi
grep -q -- "--max-wall-s" bad.out || { cat bad.out; exit 1; }
[ ! -e bad.db ] || { echo "a store was made for a refused option"; exit 1; }
echo ok
