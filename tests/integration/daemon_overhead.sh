#!/usr/bin/env bash
# The DDS path's cost: frames/s of litamin2d (one stream, one processing thread, a queue that
# never drops, scans from litamin2-replay --max) as a ratio to litamin2-odometry --threads 1 on
# the same simulated scans, measured alternately (offline, daemon, offline, daemon, ...) in one
# run. Inside a private network namespace with the loopback profile: nothing leaves the machine.
# A benchmark, not a CTest test (timing depends on the machine); see docs/benchmarks.md.
#
# offline frames/s: stats.json's frames_per_second (frames / summed tracker time per frame).
# daemon frames/s:  (results - 1) / (last result - first result), from the daemon's statistics
#                   (its shutdown summary); the replay publishes faster than the daemon
#                   processes, so its one processing thread is never idle in between.
# CPU time per frame besides: the offline tool's whole process (reading the scans included)
# and the daemon's, all threads and its busiest thread (the processing one), from
# /proc/PID/task/*/stat once every result is out; on a shared 2-core machine the frames/s
# ratio also measures the CPU that the replay and the DDS receive thread take from the
# processing thread, the CPU ratio does not.
# The probe checks that every odometry pose is bit-identical to the offline tool's and that
# nothing was dropped.
#
# The replay reads every scan before publishing (--preload; PRELOAD=0: while publishing), so that
# its disk reading does not take CPU from the daemon during the measurement.
#
# Usage: daemon_overhead.sh BUILD_DIR WORK_DIR [FRAMES=300] [ROUNDS=3]
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
frames=${3:-300}
rounds=${4:-3}
tools=$build/tools
domain=24
preload_args=()
if [ "${PRELOAD:-1}" = 1 ]; then preload_args=(--preload); fi
mkdir -p "$work"
cd "$work"
if [ ! -f seq/times.txt ] || [ "$(ls seq/velodyne | wc -l)" -ne "$frames" ]; then
  rm -rf seq
  "$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 ||
    { cat sim.log; exit 1; }
fi
cat > overhead.yaml <<YAML
dds: {domain: $domain, profile: loopback}
discovery: {enabled: false}
threads: 1
queue_depth: $((frames + 10))
outputs: {status_period_s: 0.5}
streams: [{id: overhead}]
YAML

daemon_pid=
cleanup() {
  if [ -n "$daemon_pid" ] && kill -0 "$daemon_pid" 2>/dev/null; then kill -9 "$daemon_pid"; fi
}
trap cleanup EXIT

offline_round() {  # offline_round R: writes "frames/s (tracker time), frames/s (wall), CPU
  local r=$1     # ms per frame (process)" to result
  rm -rf "offline_$r"
  /usr/bin/time -f "%U %S" -o "time_$r.txt" "$tools/odometry/litamin2-odometry" seq \
    --output "offline_$r" --threads 1 --quiet > "odometry_$r.log" 2>&1 ||
    { cat "odometry_$r.log"; exit 1; }
  python3 -c "import json,sys;s=json.load(open(sys.argv[1]));u,k=map(float,open(sys.argv[2]).read().split());
print(s['frames_per_second'], $frames/s['wall_seconds'], 1000*(u+k)/$frames)" \
    "offline_$r/stats.json" "time_$r.txt" > result
}

cpu_ticks() {  # cpu_ticks PID: "TOTAL MAX" utime+stime clock ticks over the threads of PID
  for t in /proc/"$1"/task/*; do
    # Fields after the ")" that ends the command name: utime and stime are the 12th and 13th.
    sed 's/.*) //' "$t/stat" | awk '{print $12 + $13}'
  done | awk '{s += $1; if ($1 > m) m = $1} END {print s, m}'
}

daemon_round() {  # daemon_round R: writes "frames/s (first to last result), frames/s (wall),
                  # CPU ms per frame (process, busiest thread)" to result
  local r=$1
  "$tools/litamin2d/litamin2d" --config overhead.yaml > "daemon_$r.log" 2>&1 &
  daemon_pid=$!
  rm -f probe.ready
  "$build/tests/integration/daemon_probe" --domain $domain --expect "$frames" --timeout 300 \
    --stream overhead=offline_1/poses_kitti.txt --ready-file probe.ready > "probe_$r.log" 2>&1 &
  local probe_pid=$!
  for _ in $(seq 1 300); do [ -f probe.ready ] && break; sleep 0.1; done
  [ -f probe.ready ] || { echo "probe never matched" >&2; cat "daemon_$r.log" >&2; exit 1; }
  local start end
  start=$(date +%s.%N)
  timeout 300 "$tools/replay/litamin2-replay" --domain $domain --profile loopback --max \
    "${preload_args[@]}" --depth 10 seq --stream overhead > "replay_$r.log" 2>&1 ||
    { cat "replay_$r.log" "daemon_$r.log" >&2; exit 1; }
  local probe_status=0
  wait $probe_pid || probe_status=$?
  end=$(date +%s.%N)
  local ticks
  ticks=$(cpu_ticks $daemon_pid)
  kill -TERM $daemon_pid
  wait $daemon_pid || true
  daemon_pid=
  if [ "$probe_status" -ne 0 ]; then
    cat "probe_$r.log" "daemon_$r.log" >&2
    exit 1
  fi
  # The probe waits 1.5 s after the last message before it reports: not part of the run.
  python3 - "daemon_$r.log" "$frames" "$start" "$end" $ticks "$(getconf CLK_TCK)" > result <<'PY'
import re, sys
log, frames, start, end = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
total, busiest, hz = map(float, sys.argv[5:8])
fps = None
for line in open(log):
    m = re.search(r"shut down: .*?; 1 stream\(s\), ([\d.]+) frames/s, 0 dropped, 0 bad", line)
    if m: fps = float(m.group(1))
if fps is None: sys.exit("no shutdown summary with 0 dropped in " + log)
print(fps, frames / (end - start - 1.5), 1000 * total / hz / frames, 1000 * busiest / hz / frames)
PY
  [ -s result ]
}

uptime
results=()
for r in $(seq 1 "$rounds"); do
  offline_round "$r"
  read -r off off_wall off_cpu < result
  daemon_round "$r"
  read -r dmn dmn_wall dmn_cpu dmn_thread_cpu < result
  echo "round $r: offline $off frames/s (wall $off_wall, CPU $off_cpu ms/frame);" \
    "daemon $dmn frames/s (replay start to last odometry: $dmn_wall; CPU $dmn_cpu ms/frame," \
    "processing thread $dmn_thread_cpu)"
  results+=("$off $dmn $off_cpu $dmn_cpu $dmn_thread_cpu")
done
uptime
printf '%s\n' "${results[@]}" | python3 -c "
import statistics as st, sys
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
med = lambda i: st.median(r[i] for r in rows)
ratios = [r[1] / r[0] for r in rows]
print(f'median: offline {med(0):.1f} frames/s, daemon {med(1):.1f} frames/s; daemon/offline per '
      'round ' + ', '.join(f'{x:.3f}' for x in ratios) + f'; median {st.median(ratios):.3f} '
      f'-> throughput overhead {100 * (1 - st.median(ratios)):.1f} %')
print(f'CPU per frame (median): offline {med(2):.2f} ms, daemon {med(3):.2f} ms '
      f'({100 * (med(3) / med(2) - 1):+.1f} %), of which the processing thread {med(4):.2f} ms '
      f'({100 * (med(4) / med(2) - 1):+.1f} %)')
"
grep -h "bit-identical" probe_*.log | sort | uniq -c
