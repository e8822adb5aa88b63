#!/usr/bin/env bash
# Throughput and latency of litamin2d: N simulated HDL-64 streams replayed at RATE Hz into one
# daemon (loopback profile, private network namespace); prints per-stream latency (arrival ->
# odometry published, p50/p99 from the daemon's status), frames dropped, and the offline tool's
# frames/s on the same scans for comparison. Not a CTest test (timing depends on the machine).
# QUEUE_DEPTH (default 4) sets the daemon's per-stream queue; PRELOAD=0 makes the replay read
# scans while publishing instead of before (litamin2-replay --preload); STAGGER=1 spreads the
# streams over the period (litamin2-replay --stagger).
# Usage: daemon_bench.sh BUILD_DIR WORK_DIR STREAMS [RATE_HZ=10|max] [FRAMES=30] [THREADS=0]
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
streams=$3
rate=${4:-10}
frames=${5:-30}
threads=${6:-0}
tools=$build/tools
mkdir -p "$work"
cd "$work"
if [ ! -f seq/times.txt ] || [ "$(ls seq/velodyne | wc -l)" -ne "$frames" ]; then
  rm -rf seq offline
  "$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1
fi
"$tools/odometry/litamin2-odometry" seq --output offline --threads 1 --quiet > odometry.log 2>&1
offline_fps=$(python3 -c "import json;print(json.load(open('offline/stats.json'))['frames_per_second'])")

ids=()
{
  echo "dds: {domain: 19, profile: loopback}"
  echo "discovery: {enabled: false}"
  echo "threads: $threads"
  echo "queue_depth: ${QUEUE_DEPTH:-4}"
  echo "outputs: {status_period_s: 0.5}"
  echo "streams:"
  for i in $(seq 1 "$streams"); do echo "  - id: bench_$i"; ids+=("bench_$i"); done
} > bench.yaml
"$tools/litamin2d/litamin2d" --config bench.yaml > daemon.log 2>&1 &
daemon_pid=$!
trap 'kill -9 $daemon_pid 2>/dev/null || true' EXIT
probe_args=()
replay_streams=()
replay_dirs=()
for id in "${ids[@]}"; do
  probe_args+=(--stream "$id=offline/poses_kitti.txt")
  replay_streams+=(--stream "$id")
  replay_dirs+=(seq)
done
rm -f probe.ready
"$build/tests/integration/daemon_probe" --domain 19 --expect "$frames" --timeout 60 \
  --ready-file probe.ready "${probe_args[@]}" > probe.log 2>&1 &
probe_pid=$!
for _ in $(seq 1 300); do [ -f probe.ready ] && break; sleep 0.1; done
start=$(date +%s.%N)
if [ "$rate" = max ]; then rate_args=(--max); else rate_args=(--rate "$rate"); fi
# The replay reads and converts every scan before publishing (PRELOAD=0: while publishing), so
# that on this one machine its disk reading does not take CPU from the daemon it measures.
replay_args=()
if [ "${PRELOAD:-1}" = 1 ]; then replay_args=(--preload); fi
# STAGGER=1 spreads the streams' frames over the period (independent sensors); default: every
# stream publishes at the same instant, the worst case for latency.
if [ "${STAGGER:-0}" = 1 ] && [ "$rate" != max ]; then replay_args+=(--stagger); fi
"$tools/replay/litamin2-replay" --domain 19 --profile loopback "${rate_args[@]}" "${replay_args[@]}" \
  "${replay_dirs[@]}" "${replay_streams[@]}" > replay.log 2>&1 || true
wait $probe_pid || true
end=$(date +%s.%N)
grep -E "^Vm(HWM|RSS)" /proc/$daemon_pid/status | tr -s ' \t' ' ' | paste -sd, - > memory.txt || true
kill -TERM $daemon_pid
wait $daemon_pid || true
grep -E "^status |bit-identical|PASS|FAIL" probe.log || true
echo "litamin2d memory at the end: $(cat memory.txt)"
python3 - "$streams" "$frames" "$start" "$end" "$offline_fps" <<'PY'
import re, sys
streams, frames, start, end, offline = int(sys.argv[1]), int(sys.argv[2]), *map(float, sys.argv[3:6])
p50, p99, dropped = [], [], 0
for line in open("probe.log"):
    m = re.match(r"status \S+: processed (\d+), dropped (\d+), bad \d+, p50 ([\d.]+) ms, p99 ([\d.]+) ms", line)
    if m:
        dropped += int(m.group(2)); p50.append(float(m.group(3))); p99.append(float(m.group(4)))
print(f"{streams} stream(s): latency p50 median {sorted(p50)[len(p50)//2]:.1f} ms, "
      f"worst p99 {max(p99):.1f} ms, {dropped} frame(s) dropped; offline tool {offline:.1f} frames/s "
      f"(1 thread); {streams*frames} frames in {end-start:.2f} s")
PY
