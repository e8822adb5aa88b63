#!/usr/bin/env bash
# Two LiDARs on one vehicle: litamin2-sim --second-sensor -> litamin2-replay (two topics, the
# same stamps) -> litamin2d (one stream with `topics:`, the scans merged) -> daemon_probe, in a
# private network namespace with the loopback-only profile. Checks one odometry message per
# sweep, the odometry against the simulator's ground truth (bounded error) and the merge
# counters of the status; then again with the rear sensor stopping half-way.
# Usage: daemon_two_sensors.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
tools=$build/tools
frames=40
# The rear sensor: 1.2 m behind, 0.4 m left, 0.3 m above the front one, turned 90 degrees left
# (a rotation, so that an extrinsic applied the wrong way round moves its points inconsistently).
extrinsic_cli="-1.2,0.4,0.3,0,0,90"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

echo "== simulate two sensors"
"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output front \
  --second-sensor vlp16 --second-extrinsic="$extrinsic_cli" --second-output rear > sim.log 2>&1 ||
  { cat sim.log; exit 1; }
test "$(ls front/velodyne | wc -l)" -eq $frames
test "$(ls rear/velodyne | wc -l)" -eq $frames
cat rear/extrinsic.txt
cmp front/times.txt rear/times.txt

daemon_pid=
cleanup() {
  if [ -n "$daemon_pid" ] && kill -0 "$daemon_pid" 2>/dev/null; then kill -9 "$daemon_pid"; fi
}
trap cleanup EXIT

# run_pair TAG DOMAIN FRONT_DIR REAR_DIR: litamin2d with one stream of both topics, the probe,
# and the replay of both folders; writes TAG_received_car_m.txt and TAG_status_car_m.txt.
run_pair() {
  local tag=$1 domain=$2 front_dir=$3 rear_dir=$4
  cat > $tag.yaml <<YAML
dds: {domain: $domain, profile: loopback}
streams:
  - id: car_m
    topics:
      - {topic: rt/car_m/front/points, extrinsic: {xyz: [0, 0, 0]}}
      - {topic: rt/car_m/rear/points, extrinsic: {xyz: [-1.2, 0.4, 0.3], rpy_deg: [0, 0, 90]}}
    merge_window_s: 0.05
    merge_timeout_s: 1.0
discovery: {enabled: false}
threads: 2
queue_depth: 100
outputs: {status_period_s: 0.5}
log_level: info
YAML
  echo "== $tag: start litamin2d and the probe"
  "$tools/litamin2d/litamin2d" --config $tag.yaml > ${tag}_daemon.log 2>&1 &
  daemon_pid=$!
  "$build/tests/integration/daemon_probe" --domain $domain --expect $frames --timeout 300 \
    --stream car_m --ready-file $tag.ready --poses-out ${tag}_received_ \
    --status-out ${tag}_status_ > ${tag}_probe.log 2>&1 &
  local probe_pid=$!
  for _ in $(seq 1 200); do [ -f $tag.ready ] && break; sleep 0.1; done
  test -f $tag.ready ||
    { echo "probe never matched the daemon's odometry writer"; cat ${tag}_daemon.log ${tag}_probe.log; exit 1; }
  echo "== $tag: replay both sensors' topics at 10 Hz, at the same instants"
  timeout 300 "$tools/replay/litamin2-replay" --domain $domain --profile loopback --rate 10 \
    $front_dir $rear_dir --stream car_m/front --stream car_m/rear > ${tag}_replay.log 2>&1 ||
    { cat ${tag}_replay.log ${tag}_daemon.log; exit 1; }
  local probe_status=0
  wait $probe_pid || probe_status=$?
  cat ${tag}_probe.log
  kill -TERM $daemon_pid
  local daemon_status=0
  wait $daemon_pid || daemon_status=$?
  daemon_pid=
  [ "$probe_status" -eq 0 ] || { echo "probe failed"; cat ${tag}_daemon.log; exit 1; }
  [ "$daemon_status" -eq 0 ] || { cat ${tag}_daemon.log; exit 1; }
  grep -q "stream car_m: reading rt/car_m/front/points" ${tag}_daemon.log || { cat ${tag}_daemon.log; exit 1; }
  grep -q "stream car_m: reading rt/car_m/rear/points" ${tag}_daemon.log || { cat ${tag}_daemon.log; exit 1; }
}

# check_counters TAG REAR_SCANS: one merged frame per front scan; the rear sensor's scans all
# merged, and every frame without one counted as missing; nothing rejected.
check_counters() {
  local tag=$1 rear_scans=$2 file=${1}_status_car_m.txt
  echo "== $tag: merge counters"
  cat $file
  value() { awk -v k="$1" '$1 == k { print $2 }' $file; }
  [ "$(value topic)" = "rt/car_m/front/points,rt/car_m/rear/points" ] || { echo "topic"; exit 1; }
  [ "$(value frames_received)" = "$((frames + rear_scans))" ] || { echo "frames_received"; exit 1; }
  [ "$(value merged_frames)" = "$frames" ] || { echo "merged_frames != $frames"; exit 1; }
  [ "$(value merged_frames_incomplete)" = "$((frames - rear_scans))" ] || { echo "incomplete"; exit 1; }
  [ "$(value sensor.0.scans)" = "$frames" ] || { echo "sensor 0 scans"; exit 1; }
  [ "$(value sensor.1.scans)" = "$rear_scans" ] || { echo "sensor 1 scans"; exit 1; }
  [ "$(value sensor.0.missing)" = 0 ] || { echo "sensor 0 missing"; exit 1; }
  [ "$(value sensor.1.missing)" = "$((frames - rear_scans))" ] || { echo "sensor 1 missing"; exit 1; }
  for s in 0 1; do
    for k in out_of_order late; do
      [ "$(value sensor.$s.$k)" = 0 ] || { echo "sensor $s $k"; exit 1; }
    done
  done
}

# Both sensors publish each sweep at the same instant with the same stamp: every frame complete.
run_pair both 21 front rear
check_counters both $frames

# The rear sensor stops half-way: its last 20 scans are missing from the merged frames (counted),
# the front sensor's frames are still tracked, one odometry message each.
half=$((frames / 2))
mkdir -p rear_stops/velodyne
cp rear/calib.txt rear_stops/
head -n $half rear/times.txt > rear_stops/times.txt
head -n $half rear/poses.txt > rear_stops/poses.txt
for i in $(seq 0 $((half - 1))); do
  f=$(printf '%06d.bin' $i)
  cp rear/velodyne/$f rear_stops/velodyne/$f
done
run_pair stops 22 front rear_stops
check_counters stops $half

# Scans with per-point times: each firing cast from its own pose within the sweep, both sensors'
# PCDs with a time field (relative to the sweep start, the stamp); the daemon deskews the merged
# frame (deskew is on by default) in the base frame.
echo "== simulate two sensors with motion within the sweep"
"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output sweep_front --sweep-motion \
  --second-sensor vlp16 --second-extrinsic="$extrinsic_cli" --second-output sweep_rear \
  > sim_sweep.log 2>&1 || { cat sim_sweep.log; exit 1; }
run_pair deskew 23 sweep_front/pcd sweep_rear/pcd
check_counters deskew $frames

echo "== odometry against the ground truth (the front sensor's frame is the base)"
cat > check_truth.py <<'PY'
import math, sys

def mat(v):
    return [v[0:4], v[4:8], v[8:12], [0.0, 0.0, 0.0, 1.0]]

def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]

def inv(m):
    r = [[m[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(r[i][k] * m[k][3] for k in range(3)) for i in range(3)]
    return [r[0] + [t[0]], r[1] + [t[1]], r[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]

def poses(path):
    return [mat([float(x) for x in line.split()]) for line in open(path) if line.strip()]

tr = None
for line in open(sys.argv[2]):
    if line.startswith("Tr:"):
        tr = mat([float(x) for x in line.split()[1:]])
tr_inv = inv(tr)
# poses.txt is in KITTI's camera-0 convention: the velodyne (base) pose is Tr^-1 P Tr.
truth = [mul(mul(tr_inv, p), tr) for p in poses(sys.argv[1])]
got = poses(sys.argv[3])
assert len(got) == len(truth), (len(got), len(truth))
worst = 0.0
for g, t in zip(got, truth):
    worst = max(worst, math.dist([g[i][3] for i in range(3)], [t[i][3] for i in range(3)]))
length = sum(math.dist([a[i][3] for i in range(3)], [b[i][3] for i in range(3)])
             for a, b in zip(truth, truth[1:]))
d = mul(inv(truth[-1]), got[-1])
yaw = math.degrees(math.atan2(d[1][0], d[0][0]))
print(f"{len(got)} poses over {length:.1f} m: max position error {worst:.3f} m, "
      f"final heading error {yaw:.3f} deg")
# Bound (argument 4, metres). Without motion within the sweep, 5 cm over the 31 m; measured
# (deterministic: every frame complete): 0.017 m with the right extrinsic; with the rear
# extrinsic inverted 0.160 m, with it left out (identity) 0.091 m (the map then holds ~2900
# distributions instead of ~1660: two copies of the scene). With motion within the sweep,
# 10 cm: measured 0.080 m merged and deskewed, 0.076 m for the front sensor alone offline with
# --deskew, 0.111 m for it without.
bound = float(sys.argv[4])
if worst > bound or abs(yaw) > 0.5:
    print(f"FAIL: error above {bound:.3f} m or 0.5 deg")
    sys.exit(1)
PY
python3 check_truth.py front/poses.txt front/calib.txt both_received_car_m.txt 0.05
python3 check_truth.py front/poses.txt front/calib.txt stops_received_car_m.txt 0.05
python3 check_truth.py sweep_front/poses.txt sweep_front/calib.txt deskew_received_car_m.txt 0.1
# Passed: the scans go, their poses stay (kept on failure for a look).
rm -rf ./*/velodyne ./*/pcd
echo PASS
