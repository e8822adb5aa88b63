#!/usr/bin/env bash
# The aggregator's map tiles on rt/litamin2/map_tiles and the litamin2-map-tiles client: one
# stream drives through its own synthetic scene (aggregator_probe publish --scene) into 25 m
# tiles; an early client (started before the patches) and a late one (started after the map
# settled: transient-local) of a box of tile keys get exactly the tiles in the box, each at the
# newest revision that a late client of every tile gets; changes within map_tiles.publish_period_s
# are deferred (counted); after a restart of the aggregator on the same store every tile comes
# again with a higher revision. In a private network namespace, loopback profile.
# Usage: map_tiles.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
aggregator=$build/tools/aggregator/litamin2-aggregator
client=$build/tools/map_tiles/litamin2-map-tiles
probe=$build/tests/integration/aggregator_probe
domain=48
rm -rf "$work"
mkdir -p "$work"
cd "$work"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

cat > aggregator.yaml <<YAML
dds: {domain: $domain, profile: loopback}
store: {path: tiles.db}
publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.5, tiles_period_s: 0.2}
map_tiles: {tile_size: 25, publish_period_s: 1.0}
log_level: info
YAML

start_aggregator() {
  "$aggregator" --config aggregator.yaml >> aggregator.log 2>&1 &
  aggregator_pid=$!
  pids+=("$aggregator_pid")
}
stop_aggregator() {  # SIGTERM, must exit 0 within 10 s
  kill -TERM "$aggregator_pid"
  for _ in $(seq 1 100); do kill -0 "$aggregator_pid" 2>/dev/null || break; sleep 0.1; done
  local status=0
  wait "$aggregator_pid" || status=$?
  [ "$status" -eq 0 ] || { echo "aggregator exited with $status"; cat aggregator.log; exit 1; }
}
box="--ix-min 0 --ix-max 1 --iy-min -1 --iy-max 0"

echo "== aggregator, early client of the box, 4 s of patches"
start_aggregator
"$client" --domain $domain $box --timeout 14 --json > early.json 2> early.log &
early=$!
pids+=("$early")
"$probe" --domain $domain publish --synthetic 400 --scene --speed 10 --rate 2 --duration 4 \
  --streams-count 1 --linger 1 > publish.log 2>&1 || { cat publish.log aggregator.log; exit 1; }
cat publish.log
sleep 4  # the last changes: tiles_period_s, publish_period_s, the fusion of the last keyframes

echo "== late clients: every tile, the box (with a PLY)"
"$client" --domain $domain --timeout 4 --json > all.json 2> all.log || { cat all.log; exit 1; }
"$client" --domain $domain $box --timeout 4 --json --ply box.ply > late.json 2> late.log ||
  { cat late.log; exit 1; }
wait "$early" || { echo "early client failed"; cat early.log; exit 1; }
stop_aggregator
grep "map tiles:" aggregator.log | tail -1 | sed 's/^info: //' 

echo "== restart on the same store: every tile again, later revisions"
start_aggregator
"$client" --domain $domain --timeout 5 --json > restart.json 2> restart.log ||
  { cat restart.log; exit 1; }
stop_aggregator

python3 - "$box" <<'PY'
import json, sys
def tiles(name):
    j = json.load(open(name))
    assert sum(j["rejected"].values()) == 0, (name, j["rejected"])
    return {(t["ix"], t["iy"]): t for t in j["tiles"]}
everything, early, late, again = (tiles(f + ".json") for f in ("all", "early", "late", "restart"))
in_box = {k: t for k, t in everything.items() if 0 <= k[0] <= 1 and -1 <= k[1] <= 0}
print(f"{len(everything)} tiles in the map, {len(in_box)} in the box; early client "
      f"{len(early)}, late {len(late)}")
assert len(everything) >= 8, "too few tiles for the test"
assert len(in_box) >= 2 and len(in_box) < len(everything)
for name, got in (("early", early), ("late", late)):
    assert set(got) == set(in_box), (name, sorted(got), sorted(in_box))
    for k, t in got.items():
        assert t["revision"] == in_box[k]["revision"], (name, k, t["revision"], in_box[k]["revision"])
        assert t["distributions"] == in_box[k]["distributions"] and t["distributions"] > 0, (name, k)
        assert t["frame_id"] == "map" and t["tile_size"] == 25.0
early_samples = json.load(open("early.json"))["accepted"]
print(f"early client: {early_samples} samples for {len(early)} tiles")
assert early_samples > len(early), "the early client should have seen tiles change"
assert set(again) == set(everything), (sorted(again), sorted(everything))
for k, t in again.items():
    assert t["revision"] > everything[k]["revision"], ("revision after restart", k)
    assert t["distributions"] == everything[k]["distributions"], ("same map after restart", k)
ply_vertices = int(next(l for l in open("box.ply", "rb").read().split(b"end_header")[0].decode().splitlines()
                        if l.startswith("element vertex")).split()[2])
assert ply_vertices == sum(t["distributions"] for t in late.values()), ply_vertices
print(f"box PLY: {ply_vertices} means; revisions increase across the restart")
# Where the box was filtered (informative, not asserted: Fast DDS decides): samples each
# client's own filter evaluated (0: its writer filtered for it).
for f in ("early", "late", "all", "restart"):
    print(f"{f} client: its filter evaluated {json.load(open(f + '.json'))['filter_evaluations_here']} sample(s)")
PY
deferred=$(grep "map tiles:" aggregator.log | head -1 | sed -E 's/.* ([0-9]+) deferred.*/\1/')
echo "first run: $deferred change(s) deferred by publish_period_s"
[ "$deferred" -gt 0 ] || { echo "no change was deferred: the period is not exercised"; exit 1; }
echo "ok"
