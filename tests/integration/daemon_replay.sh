#!/usr/bin/env bash
# simulated scans -> litamin2-replay -> litamin2d -> daemon_probe, in a private network
# namespace. Usage: daemon_replay.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
source_dir=$3
tools=$build/tools
frames=30
rm -rf "$work"
mkdir -p "$work"
cd "$work"

echo "== simulate and run the offline odometry"
"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 ||
  { cat sim.log; exit 1; }
"$tools/odometry/litamin2-odometry" seq --output offline --quiet > odometry.log 2>&1 ||
  { cat odometry.log; exit 1; }
test "$(wc -l < offline/poses_kitti.txt)" -eq $frames

cat > litamin2d.yaml <<YAML
dds: {domain: 17, profile: loopback}
streams:
  - id: car_a
  - id: car_b
discovery: {enabled: false}
threads: 2
queue_depth: 100
outputs: {status_period_s: 0.5}
log_level: info
YAML

daemon_pid=
cleanup() {
  if [ -n "$daemon_pid" ] && kill -0 "$daemon_pid" 2>/dev/null; then kill -9 "$daemon_pid"; fi
}
trap cleanup EXIT

echo "== start litamin2d and the probe"
"$tools/litamin2d/litamin2d" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
"$build/tests/integration/daemon_probe" --domain 17 --expect $frames --timeout 300 \
  --stream car_a=offline/poses_kitti.txt --stream car_b=offline/poses_kitti.txt \
  --ready-file probe.ready --poses-out received_ > probe.log 2>&1 &
probe_pid=$!
for _ in $(seq 1 200); do [ -f probe.ready ] && break; sleep 0.1; done
test -f probe.ready || { echo "probe never matched the daemon's odometry writers"; cat daemon.log probe.log; exit 1; }

echo "== replay both streams at full speed (scans preloaded)"
start=$(date +%s.%N)
timeout 300 "$tools/replay/litamin2-replay" --domain 17 --profile loopback --max --preload \
  seq seq --stream car_a --stream car_b > replay.log 2>&1 || { cat replay.log daemon.log; exit 1; }
probe_status=0
wait $probe_pid || probe_status=$?
end=$(date +%s.%N)
cat probe.log
echo "replay + processing of 2 x $frames frames: $(echo "$end - $start" | bc) s"

echo "== SIGTERM"
t0=$(date +%s%N)
kill -TERM $daemon_pid
daemon_status=0
for _ in $(seq 1 50); do kill -0 $daemon_pid 2>/dev/null || break; sleep 0.05; done
if kill -0 $daemon_pid 2>/dev/null; then
  echo "litamin2d still running 2.5 s after SIGTERM"; cat daemon.log; exit 1
fi
wait $daemon_pid || daemon_status=$?
t1=$(date +%s%N)
daemon_pid=
ms=$(( (t1 - t0) / 1000000 ))
echo "litamin2d exited with $daemon_status, ${ms} ms after SIGTERM"
tail -n 5 daemon.log
[ "$probe_status" -eq 0 ] || { echo "probe failed"; cat daemon.log; exit 1; }
[ "$daemon_status" -eq 0 ] || exit 1
[ "$ms" -lt 2000 ] || exit 1

echo "== discovery: a daemon on the shipped default finds rt/car_c/points by itself"
# The shipped file sets no dds.domain: ROS_DOMAIN_ID chooses it, as for a ROS 2 node.
ROS_DOMAIN_ID=18 "$tools/litamin2d/litamin2d" --config "$source_dir/config/litamin2d.yaml" \
  > daemon_discovery.log 2>&1 &
daemon_pid=$!
rm -f probe.ready
"$build/tests/integration/daemon_probe" --domain 18 --expect $frames --timeout 300 \
  --stream car_c=offline/poses_kitti.txt --ready-file probe.ready > probe_discovery.log 2>&1 &
probe_pid=$!
# The daemon creates car_c's odometry writer when it discovers the replay's writer; the probe
# needs a moment to match it before the first scan's odometry is published. 2 s was once not
# enough on a loaded machine (the probe matched ~3 s after the writer's creation and missed
# the first 10 messages: a discovery message resent after Fast DDS's builtin heartbeat), so 5.
timeout 300 "$tools/replay/litamin2-replay" --domain 18 --profile loopback --rate 10 \
  --start-delay 5 seq --stream car_c > replay_discovery.log 2>&1 || { cat replay_discovery.log daemon_discovery.log; exit 1; }
probe_status=0
wait $probe_pid || probe_status=$?
cat probe_discovery.log
kill -TERM $daemon_pid
daemon_status=0
wait $daemon_pid || daemon_status=$?
daemon_pid=
grep -q "stream car_c: reading rt/car_c/points" daemon_discovery.log || { cat daemon_discovery.log; exit 1; }
grep -q "DDS participant up: domain 18 (ROS_DOMAIN_ID)" daemon_discovery.log ||
  { echo "ROS_DOMAIN_ID not used"; cat daemon_discovery.log; exit 1; }
[ "$probe_status" -eq 0 ] || { echo "discovery probe failed"; cat daemon_discovery.log; exit 1; }
[ "$daemon_status" -eq 0 ] || exit 1
echo PASS
