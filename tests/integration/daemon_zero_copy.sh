#!/usr/bin/env bash
# The opt-in same-host zero-copy input: simulated scans -> litamin2-replay --zero-copy
# (litamin2_zero_copy/PlainScan in loaned samples) -> litamin2d (streams[].zero_copy_topic, data-sharing
# reader, loans on take) -> daemon_probe, in a private network namespace, loopback profile.
# Every frame of two parallel streams gets one odometry message whose pose is bit-identical to
# litamin2-odometry's; no bad message, no drop; the writers' data-sharing segments appear in
# /dev/shm while the replay runs. Usage: daemon_zero_copy.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
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
dds: {domain: 19, profile: loopback}
streams:
  - id: car_a
    zero_copy_topic: rt/car_a/plain_scan
  - id: car_b
    zero_copy_topic: rt/car_b/plain_scan
discovery: {enabled: false}
threads: 2
queue_depth: 100
outputs: {status_period_s: 0.5}
log_level: info
YAML

daemon_pid=
sampler_pid=
cleanup() {
  if [ -n "$daemon_pid" ] && kill -0 "$daemon_pid" 2>/dev/null; then kill -9 "$daemon_pid"; fi
  if [ -n "$sampler_pid" ] && kill -0 "$sampler_pid" 2>/dev/null; then kill "$sampler_pid"; fi
}
trap cleanup EXIT

echo "== start litamin2d and the probe"
"$tools/litamin2d/litamin2d" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
"$build/tests/integration/daemon_probe" --domain 19 --expect $frames --timeout 60 \
  --stream car_a=offline/poses_kitti.txt --stream car_b=offline/poses_kitti.txt \
  --ready-file probe.ready > probe.log 2>&1 &
probe_pid=$!
for _ in $(seq 1 200); do [ -f probe.ready ] && break; sleep 0.1; done
test -f probe.ready || { echo "probe never matched the daemon's odometry writers"; cat daemon.log probe.log; exit 1; }

# At 10 Hz: a reliable data-sharing reader acknowledges a sample when it is notified of it, not
# when it takes it, so at --max a loaded machine's listener thread could fall more than the
# writer's pool (depth 10 + extra samples) behind; the daemon would then count those samples
# overwritten (bad messages) and this test would fail.
echo "== replay both streams at 10 Hz as PlainScan (loaned samples)"
# The data-sharing segments Fast DDS makes for the writers (fast_datasharing_*), sampled while
# the replay runs (bounded: 600 x 0.1 s).
( for _ in $(seq 1 600); do ls /dev/shm 2>/dev/null | grep '^fast_datasharing' || true; sleep 0.1; done ) \
  > shm_segments.txt &
sampler_pid=$!
timeout 300 "$tools/replay/litamin2-replay" --domain 19 --profile loopback --rate 10 --zero-copy \
  seq seq --stream car_a --stream car_b > replay.log 2>&1 || { cat replay.log daemon.log; exit 1; }
kill "$sampler_pid" 2>/dev/null || true
wait "$sampler_pid" 2>/dev/null || true
sampler_pid=
probe_status=0
wait $probe_pid || probe_status=$?
cat probe.log
tail -n 3 replay.log

kill -TERM $daemon_pid
daemon_status=0
wait $daemon_pid || daemon_status=$?
daemon_pid=
tail -n 5 daemon.log
[ "$probe_status" -eq 0 ] || { echo "probe failed"; cat daemon.log; exit 1; }
[ "$daemon_status" -eq 0 ] || exit 1
grep -q "stream car_a: reading rt/car_a/plain_scan (zero-copy" daemon.log ||
  { echo "no zero-copy reader"; cat daemon.log; exit 1; }
if grep -q "dropped a bad" daemon.log; then echo "bad messages"; cat daemon.log; exit 1; fi
grep -q "2 stream(s), .* 0 dropped, 0 bad messages" daemon.log ||
  { echo "drops or bad messages"; cat daemon.log; exit 1; }
segments=$(sort -u shm_segments.txt | wc -l)
echo "data-sharing segments seen in /dev/shm: $segments"
[ "$segments" -gt 0 ] || { echo "no data-sharing segment: Fast DDS did not use data-sharing"; exit 1; }
echo PASS
