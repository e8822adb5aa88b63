#!/usr/bin/env bash
# Ingest cost of litamin2-aggregator (not a ctest): STREAMS streams each publishing one map
# patch of DISTRIBUTIONS random distributions per second for DURATION s (aggregator_probe
# publish --synthetic), in a private network namespace with the loopback profile. Reports the
# aggregator's CPU time over the publishing window (utime + stime from /proc/<pid>/stat) as a
# fraction of one core, and the keyframes stored.
# Usage: aggregator_bench.sh BUILD_DIR WORK_DIR   (env STREAMS=100 DISTRIBUTIONS=3000 DURATION=60,
#   SCENE=1: --scene patches (each stream drives through its own scene; see aggregator_probe),
#   PERF=1: also `perf record` the aggregator over the window into WORK_DIR/perf.data)
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
streams=${STREAMS:-100}
distributions=${DISTRIBUTIONS:-3000}
duration=${DURATION:-60}
scene=${SCENE:+--scene}
aggregator=$build/tools/aggregator/litamin2-aggregator
probe=$build/tests/integration/aggregator_probe
rm -rf "$work"
mkdir -p "$work"
cd "$work"
cat > bench.yaml <<YAML
dds: {domain: 45, profile: loopback}
store: {path: bench.db}
log_level: info
YAML
"$aggregator" --config bench.yaml > aggregator.log 2>&1 &
pid=$!
trap 'kill -9 $pid 2>/dev/null || true' EXIT
sleep 1
ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
hz=$(getconf CLK_TCK)
"$probe" --domain 45 publish --synthetic "$distributions" --streams-count "$streams" --rate 1 \
  $scene --duration 1 --linger 0 > warmup.log 2>&1   # discovery and first allocation out of the way
sleep 2
c0=$(ticks)
t0=$(date +%s.%N)
perf_pid=
if [ -n "${PERF:-}" ]; then
  perf record -F 250 -g -p $pid -o perf.data > perf.log 2>&1 &
  perf_pid=$!
fi
"$probe" --domain 45 publish --synthetic "$distributions" --streams-count "$streams" --rate 1 \
  $scene --duration "$duration" > publish.log 2>&1
# Until the aggregator has caught up (queue empty): status is in the log only at shutdown, so
# wait for its CPU to go quiet.
prev=$(ticks)
for _ in $(seq 1 600); do sleep 1; now=$(ticks); [ $((now - prev)) -le $((hz / 50)) ] && break; prev=$now; done
c1=$(ticks)
t1=$(date +%s.%N)
if [ -n "$perf_pid" ]; then kill -INT $perf_pid; wait $perf_pid || true; fi
kill -TERM $pid
wait $pid || true
grep -E "shut down|CPU by stage" aggregator.log
cat publish.log
echo "$streams streams x 1 patch/s x $distributions distributions${scene:+ (scene)}, ${duration} s:"
echo "aggregator CPU $(echo "scale=2; ($c1 - $c0) / $hz" | bc) s over $(echo "$t1 - $t0" | bc) s wall:" \
  "$(echo "scale=2; 100 * ($c1 - $c0) / $hz / ($t1 - $t0)" | bc) % of one core"
echo "store: $(stat -c %s bench.db) bytes"
