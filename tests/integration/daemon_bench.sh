#!/usr/bin/env bash
# Throughput and latency of litamin2d: N simulated HDL-64 streams replayed at RATE Hz into one
# daemon (loopback profile, private network namespace); prints per-stream latency (arrival ->
# odometry published, p50/p99 from the daemon's status), frames dropped, and the offline tool's
# frames/s on the same scans for comparison. Not a CTest test (timing depends on the machine).
#
# Usage: daemon_bench.sh BUILD_DIR WORK_DIR STREAMS [RATE_HZ=10|max] [FRAMES=30] [THREADS=0]
# Environment:
#   QUEUE_DEPTH  the daemon's per-stream queue (default 4)
#   PREFAULT_MB  the daemon's memory.prefault_mb (default: the key left out, so auto: 64 MiB and
#                32 a stream touched at start); 0 = the heap not touched before the first scan;
#                recorded in the JSON as prefault_mb
#   PRELOAD=0    the replay reads scans while publishing instead of publishing CDR bytes
#                serialised before the start (litamin2-replay --preload, the default)
#   STAGGER=1    spread the streams over the period (litamin2-replay --stagger)
#   BEST_EFFORT=1  the replay's writers best effort keep-last (litamin2-replay --best-effort), as
#                ROS 2 LiDAR drivers publish (sensor-data QoS): the daemon's readers match them,
#                so nothing is acknowledged; a scan the daemon's reader has no room for is lost
#                and counted as dropped (default: reliable keep-all, nothing lost)
#   ZERO_COPY=1  the streams' opt-in same-host zero-copy input instead of PointCloud2: each
#                stream gets zero_copy_topic rt/<id>/plain_scan and the replay publishes
#                litamin2_zero_copy/PlainScan there into loaned samples (litamin2-replay
#                --zero-copy, scans read before the start as with --preload; PRELOAD is ignored)
#   PIN=1        one core each: the replay and the probe on CPU 0, litamin2d with one worker
#                thread (threads: 1) on CPU 1, the offline run on CPU 1 too (taskset), so the
#                figures are one daemon core's capacity
#   SENSOR=NAME  the simulator's sensor (default hdl64; vlp16 for VLP-16-size streams)
#   FRAME_SHIFT=S  independent streams: stream k replays FRAMES scans from frame (k-1)*S of one
#                longer simulated sequence (seq_long, FRAMES + (STREAMS-1)*S frames of the
#                builtin loop, which has 387), each checked against its own offline run
#                (streams/<k>/offline), instead of every stream replaying the same FRAMES
#                scans (the default, 0). With the same scans, a frame that costs more (a
#                re-grid, a keyframe) arrives on every stream within one period; real sensors'
#                costly frames do not line up. Recorded in the JSON as frame_shift
#   JSON=FILE    write the run's figures as JSON: streams, rate_hz, frames_expected,
#                frames_processed, dropped (frames not processed: dropped_by_daemon from its
#                status, and, where probe_timed_out, those not processed when the probe stopped
#                waiting), latency_ms_p50 (median of the streams' p50),
#                latency_ms_p99 (worst stream's p99), e2e_latency_ms_p50 / _p99_all_frames /
#                _p99_worst_stream (from each scan's slot in the replay's schedule to the probe's
#                reception of its odometry: includes the transport and the wait before the
#                daemon's receive thread takes the scan, which latency_ms_* leave out),
#                e2e_latency_ms_p50_steady / _p99_steady_all_frames / _p99_steady_worst_stream
#                (the same from frame STEADY_FROM, default 20, on: after the start, where every
#                stream's first scans arrive at once), steady_from_frame,
#                replay_latest_start_ms and replay_writes_over_5ms_late (the replay's own delay:
#                the latest write's start after its slot, and the writes over 5 ms late),
#                daemon_cpu_ms_per_frame (the daemon's
#                utime+stime from the first publication to the end, per frame processed),
#                tracking_cpu_ms_per_frame (its trackers' thread CPU in Tracker::process, from
#                the daemon's status), dds_path_cpu_ms_per_frame (their difference: taking,
#                deserialising, converting, publishing) and dds_path_share_of_tracking, all from
#                one run; daemon_threads_cpu_ms_per_frame (the same CPU split by thread:
#                stream_worker = tracking + publishing, main, other = Fast DDS's receive and
#                event threads); worker_run_delay_ms_per_frame (the workers' time waiting for
#                a core while runnable, schedstat); daemon_threads_run_delay_ms_per_frame
#                (the same by thread kind: the receive threads' wait comes before a scan's
#                arrival is stamped, so the latency leaves it out); with PIN=1
#                other_processes_share_of_daemon_core (CPU 1's busy time not the daemon's, over
#                the wall time: other load that delays the daemon's frames); offline_cpu_ms_per_frame (the offline tool's wall time per frame, 1
#                thread, for comparison); daemon_minor_faults_per_frame (the daemon's page faults
#                from the first publication to the end, per frame: pages written for the first
#                time), daemon_memory_at_end (VmHWM, VmRSS), prefault_mb (PREFAULT_MB)
#   TRACKER=YAML the tracker's config (over the defaults), a YAML flow mapping written as the
#                daemon's `tracker:` key and given to the offline run (--config), e.g.
#                '{recovery: {first_speeds: []}}'; recorded in the JSON as tracker
#   SCHEDULING=YAML  the daemon's worker scheduling, a YAML flow mapping written as its
#                `scheduling:` key, e.g. '{policy: fifo, priority: 10}' (docs/deploy.md,
#                "Real-time stream workers"); recorded in the JSON with the kernel's RT throttling
#                (sched_rt_runtime_us / sched_rt_period_us, read, never changed)
#   DAEMON_PREFIX=CMD  a command litamin2d is started under (after taskset), split on spaces,
#                e.g. 'chrt -f 10': every thread of the process SCHED_FIFO 10, as systemd's
#                CPUSchedulingPolicy=fifo / CPUSchedulingPriority=10 would set it; recorded in the
#                JSON as daemon_prefix
#   PUBLISHER_PREFIX=CMD  the same for the replay and the probe (after taskset), e.g.
#                'chrt -f 10': other processes on CPU 0 then cannot delay the publication
#                (a late replay publishes its scans in a burst); recorded as publisher_prefix
#   PROBE_TIMEOUT=S  how long the probe waits for the odometry (default 60 + STREAMS * FRAMES / 20
#                s), counted from before the replay's preload (20-28 s for 32 x 100 HDL-64-size
#                scans on a 2-core VM): a run that drops frames ends after it
#   CORE_LOAD=1  competing load on the daemon's core (needs PIN=1): one busy loop on CPU 1 at
#                nice CORE_LOAD_NICE (default 10) in a session of its own (setsid: its own
#                autogroup, as another login's or service's process), started before the
#                daemon and killed when the run ends (bounded by timeout in any case); recorded
#                in the JSON as core_load
#   SEARCH=1     find the largest stream count with 0 dropped and p99 < P99_MS (default 20):
#                doubles from STREAMS until a run fails, then bisects; each run's JSON in
#                WORK_DIR/search/<n>.json and the answer in JSON (or printed);
#                SEARCH_TRIES=K runs a failing count up to K times and counts it as passing if
#                one run passes (default 1): on a shared VM one slow run (the same frames'
#                tracking CPU 35 % higher) otherwise ends the doubling; every try is in the JSON
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$(cd "$1" && pwd)
work=$2
streams=$3
rate=${4:-10}
frames=${5:-30}
threads=${6:-0}
tools=$build/tools
sensor=${SENSOR:-hdl64}
mkdir -p "$work"
work=$(cd "$work" && pwd)
cd "$work"

daemon_cpu=()
replay_cpu=()
if [ "${PIN:-0}" = 1 ]; then
  [ "$(nproc)" -ge 2 ] || { echo "PIN=1 needs two CPUs" >&2; exit 1; }
  daemon_cpu=(taskset -c 1)
  replay_cpu=(taskset -c 0)
  threads=1
fi
daemon_prefix=()
if [ -n "${DAEMON_PREFIX:-}" ]; then read -r -a daemon_prefix <<<"$DAEMON_PREFIX"; fi
# PUBLISHER_PREFIX: the same for the replay and the probe (e.g. 'chrt -f 10', so that other
# processes on CPU 0 do not delay the publication and bunch the scans).
if [ -n "${PUBLISHER_PREFIX:-}" ]; then
  read -r -a publisher_prefix <<<"$PUBLISHER_PREFIX"
  replay_cpu+=("${publisher_prefix[@]}")
fi

if [ ! -f "seq/times.txt" ] || [ "$(ls seq/velodyne | wc -l)" -ne "$frames" ] ||
  [ "$(cat seq/sensor 2>/dev/null)" != "$sensor" ]; then
  rm -rf seq offline
  "$tools/sim/litamin2-sim" --builtin loop --sensor "$sensor" --frames 0:$frames --output seq \
    > sim.log 2>&1
  echo "$sensor" > seq/sensor
fi
# The offline run with the same tracker config as the daemon (TRACKER), redone when it changes:
# offline_run INPUT_DIR OUTPUT_DIR. seq's (offline/) gives the offline tool's time a frame; with
# FRAME_SHIFT each stream's folder also has its own (streams/<k>/offline/), the probe's poses.
tracker_args=()
if [ -n "${TRACKER:-}" ]; then
  echo "$TRACKER" > tracker.yaml
  tracker_args=(--config "$work/tracker.yaml")
fi
# Also redone when the offline tool was rebuilt (its checksum is kept beside the config).
odometry_sum=$(cksum < "$tools/odometry/litamin2-odometry")
offline_run() {
  local input=$1 output=$2
  local made_by="${TRACKER:-} $odometry_sum"
  if [ ! -f "$output/stats.json" ] ||
    [ "$(cat "$output/tracker.txt" 2>/dev/null)" != "$made_by" ]; then
    rm -rf "$output"
    "${daemon_cpu[@]}" "$tools/odometry/litamin2-odometry" "$input" --output "$output" \
      --threads 1 --quiet "${tracker_args[@]}" > "$work/odometry.log" 2>&1
    echo "$made_by" > "$output/tracker.txt"
  fi
}
offline_run seq offline

# FRAME_SHIFT=S: stream k's own folder, streams/<k>: FRAMES scans from frame (k-1)*S of
# seq_long (links to its scans; its stamps, so they keep increasing), and its offline run.
frame_shift=${FRAME_SHIFT:-0}
stream_dirs() {
  local n=$1 needed=$((frames + ($1 - 1) * frame_shift)) k
  if [ ! -f seq_long/times.txt ] || [ "$(ls seq_long/velodyne | wc -l)" -lt "$needed" ] ||
    [ "$(cat seq_long/sensor 2>/dev/null)" != "$sensor" ]; then
    rm -rf seq_long streams
    "$tools/sim/litamin2-sim" --builtin loop --sensor "$sensor" --frames 0:$needed \
      --output seq_long > sim_long.log 2>&1 ||
      { echo "litamin2-sim could not make $needed frames (sim_long.log)" >&2; exit 1; }
    echo "$sensor" > seq_long/sensor
  fi
  for k in $(seq 1 "$n"); do
    local dir=streams/$k first=$(((k - 1) * frame_shift))
    if [ ! -f "$dir/times.txt" ]; then
      mkdir -p "$dir/velodyne"
      for i in $(seq 0 $((frames - 1))); do
        ln -sf "$work/seq_long/velodyne/$(printf %06d $((first + i))).bin" \
          "$dir/velodyne/$(printf %06d "$i").bin"
      done
      sed -n "$((first + 1)),$((first + frames))p" seq_long/times.txt > "$dir/times.txt"
      sed -n "$((first + 1)),$((first + frames))p" seq_long/poses.txt > "$dir/poses.txt"
      cp seq_long/calib.txt "$dir/calib.txt"
    fi
    offline_run "$dir" "$dir/offline"
  done
}
read -r offline_fps points_per_scan < <(python3 -c "
import json, os
s = json.load(open('offline/stats.json'))
n = os.path.getsize(sorted(os.scandir('seq/velodyne'), key=lambda e: e.name)[0].path) // 16
print(s['frames_per_second'], n)")

# Every thread of process $1: tid, name (comm, spaces removed), utime + stime in clock ticks.
thread_cpu() {
  local t
  for t in /proc/"$1"/task/*; do
    [ -r "$t/stat" ] || continue
    # The name is in parentheses and may hold spaces: fields are counted after the last ')'.
    # The time it waited on a run queue while runnable (ns, schedstat's second field).
    local delay
    delay=$(awk '{print $2}' "$t/schedstat" 2>/dev/null || echo 0)
    sed -E 's/^([0-9]+) \((.*)\) /\1 \2\t/' "$t/stat" |
      awk -F'\t' -v delay="${delay:-0}" '{split($2, f, " "); n = $1; sub(/ .*/, "", n);
                   name = $1; sub(/^[0-9]+ /, "", name); gsub(/ /, "_", name);
                   print n, name, f[12] + f[13], delay}'
  done
}

# Busy ticks of CPU $1 (all processes), from /proc/stat: total minus idle and iowait.
cpu_busy() {
  awk -v cpu="cpu$1" '$1 == cpu {print $2 + $3 + $4 + $7 + $8 + $9}' /proc/stat
}

# One run with N streams into a fresh daemon; its figures go to run_N/result.json.
run_once() {
  local n=$1 dir=run_$1
  rm -rf "$dir" && mkdir -p "$dir"
  [ "$frame_shift" = 0 ] || stream_dirs "$n"
  local ids=()
  {
    echo "dds: {domain: 19, profile: loopback}"
    echo "discovery: {enabled: false}"
    echo "threads: $threads"
    echo "queue_depth: ${QUEUE_DEPTH:-4}"
    if [ -n "${PREFAULT_MB:-}" ]; then echo "memory: {prefault_mb: $PREFAULT_MB}"; fi
    if [ -n "${SCHEDULING:-}" ]; then echo "scheduling: $SCHEDULING"; fi
    if [ -n "${TRACKER:-}" ]; then echo "tracker: $TRACKER"; fi
    echo "outputs: {status_period_s: 0.5}"
    echo "streams:"
    for i in $(seq 1 "$n"); do
      echo "  - id: bench_$i"
      if [ "${ZERO_COPY:-0}" = 1 ]; then echo "    zero_copy_topic: rt/bench_$i/plain_scan"; fi
      ids+=("bench_$i")
    done
  } > "$dir/bench.yaml"
  local load_pid=""
  if [ "${CORE_LOAD:-0}" = 1 ]; then
    [ "${PIN:-0}" = 1 ] || { echo "CORE_LOAD=1 needs PIN=1" >&2; exit 1; }
    # Bounded: the probe's timeout plus the replay's preload and a margin.
    setsid taskset -c 1 nice -n "${CORE_LOAD_NICE:-10}" \
      timeout $((180 + n * frames / 20)) sh -c 'while :; do :; done' &
    load_pid=$!
  fi
  "${daemon_cpu[@]}" "${daemon_prefix[@]}" "$tools/litamin2d/litamin2d" --config "$dir/bench.yaml" \
    > "$dir/daemon.log" 2>&1 &
  local daemon_pid=$!
  local probe_args=() replay_streams=() replay_dirs=() k=0
  for id in "${ids[@]}"; do
    k=$((k + 1))
    replay_streams+=(--stream "$id")
    if [ "$frame_shift" = 0 ]; then
      probe_args+=(--stream "$id=offline/poses_kitti.txt")
      replay_dirs+=(seq)
    else
      probe_args+=(--stream "$id=streams/$k/offline/poses_kitti.txt")
      replay_dirs+=("streams/$k")
    fi
  done
  rm -f "$dir/probe.ready"
  "${replay_cpu[@]}" "$build/tests/integration/daemon_probe" --domain 19 --expect "$frames" \
    --timeout "${PROBE_TIMEOUT:-$((60 + n * frames / 20))}" --ready-file "$dir/probe.ready" \
    --arrivals-out "$dir/arrivals_" "${probe_args[@]}" \
    > "$dir/probe.log" 2>&1 &
  local probe_pid=$!
  for _ in $(seq 1 300); do [ -f "$dir/probe.ready" ] && break; sleep 0.1; done
  local rate_args replay_args=()
  if [ "$rate" = max ]; then rate_args=(--max); else rate_args=(--rate "$rate"); fi
  # The replay serialises every scan before publishing (PRELOAD=0: reads while publishing), so
  # that on this one machine it does not take CPU from the daemon it measures.
  if [ "${PRELOAD:-1}" = 1 ]; then replay_args=(--preload); fi
  if [ "${ZERO_COPY:-0}" = 1 ]; then replay_args=(--zero-copy); fi
  # STAGGER=1 spreads the streams' frames over the period (independent sensors); default: every
  # stream publishes at the same instant, the worst case for latency.
  if [ "${STAGGER:-0}" = 1 ] && [ "$rate" != max ]; then replay_args+=(--stagger); fi
  if [ "${BEST_EFFORT:-0}" = 1 ]; then replay_args+=(--best-effort); fi
  # The daemon's CPU is counted from when the replay starts publishing (after its preload and
  # discovery), read from /proc/<pid>/stat (utime + stime, clock ticks).
  "${replay_cpu[@]}" "$tools/replay/litamin2-replay" --domain 19 --profile loopback \
    "${rate_args[@]}" "${replay_args[@]}" "${replay_dirs[@]}" "${replay_streams[@]}" \
    > "$dir/replay.log" 2>&1 &
  local replay_pid=$!
  local cpu_start="" faults_start="" faults_end=""
  for _ in $(seq 1 6000); do
    if grep -qE "publishing [0-9]+ frames" "$dir/replay.log" 2>/dev/null ||
      ! kill -0 $replay_pid 2>/dev/null; then break; fi
    sleep 0.05
  done
  cpu_start=$(awk '{print $14 + $15}' /proc/$daemon_pid/stat)
  faults_start=$(awk '{print $10}' /proc/$daemon_pid/stat)
  thread_cpu "$daemon_pid" > "$dir/threads_start.txt"
  local core_start=0 core_end=0
  [ "${PIN:-0}" != 1 ] || core_start=$(cpu_busy 1)
  local start end
  start=$(date +%s.%N)
  wait $replay_pid || true
  wait $probe_pid || true
  end=$(date +%s.%N)
  local cpu_end
  cpu_end=$(awk '{print $14 + $15}' /proc/$daemon_pid/stat)
  faults_end=$(awk '{print $10}' /proc/$daemon_pid/stat)
  thread_cpu "$daemon_pid" > "$dir/threads_end.txt"
  [ "${PIN:-0}" != 1 ] || core_end=$(cpu_busy 1)
  grep -E "^Vm(HWM|RSS)" /proc/$daemon_pid/status | tr -s ' \t' ' ' | paste -sd, - \
    > "$dir/memory.txt" || true
  kill -TERM $daemon_pid
  wait $daemon_pid || true
  if [ -n "$load_pid" ]; then
    kill -TERM $load_pid 2>/dev/null || true
    wait $load_pid 2>/dev/null || true
  fi
  python3 - "$n" "$frames" "$start" "$end" "$offline_fps" "$cpu_start" "$cpu_end" \
    "$(getconf CLK_TCK)" "$rate" "$points_per_scan" "$dir" "$daemon_pid" "$core_start" "$core_end" \
    "$faults_start" "$faults_end" <<'PY'
import json, os, re, sys
n, frames = int(sys.argv[1]), int(sys.argv[2])
start, end, offline_fps = map(float, sys.argv[3:6])
cpu_start, cpu_end, ticks = float(sys.argv[6]), float(sys.argv[7]), float(sys.argv[8])
rate, points, out = sys.argv[9], int(sys.argv[10]), sys.argv[11]
p50, p99, dropped, processed, tracking_s = [], [], 0, 0, 0.0
probe_timed_out = False
for line in open(out + "/probe.log"):
    if line.startswith("timed out after"):
        probe_timed_out = True
    m = re.match(r"status \S+: processed (\d+), dropped (\d+), bad \d+, p50 ([\d.]+) ms, "
                 r"p99 ([\d.]+) ms, map \d+, tracking cpu ([\d.]+) s", line)
    if m:
        processed += int(m.group(1)); dropped += int(m.group(2))
        p50.append(float(m.group(3))); p99.append(float(m.group(4)))
        tracking_s += float(m.group(5))
expected = n * frames
# The daemon's CPU from the first publication to the end, per frame processed, and the part of
# it its trackers spent in Tracker::process (thread CPU clocks, the daemon's own status): what
# is left is the DDS path (taking, deserialising, converting, publishing odometry, patches and
# status) and the daemon's other threads.
daemon_ms = (cpu_end - cpu_start) / ticks * 1000.0 / processed if processed else None
tracking_ms = tracking_s * 1000.0 / processed if processed else None
offline_ms = 1000.0 / offline_fps
# The daemon's CPU by thread (the same window, clock ticks): the stream workers (tracking and
# publishing), the main thread (discovery, status), and the others (Fast DDS's receive threads:
# taking and converting scans; its event thread: heartbeats and acknowledgements).
def thread_ticks(path):
    out = {}
    for line in open(path):
        tid, name, used, delay = line.split()
        out[tid] = (name, float(used), float(delay))
    return out
t0, t1 = thread_ticks(out + "/threads_start.txt"), thread_ticks(out + "/threads_end.txt")
pid = sys.argv[12]
by_kind, delay_by_kind = {}, {}
for tid, (name, used, delay) in t1.items():
    kind = "main" if tid == pid else ("stream_worker" if name == "stream-worker" else "other")
    by_kind[kind] = by_kind.get(kind, 0.0) + used - t0.get(tid, (name, 0.0, 0.0))[1]
    delay_by_kind[kind] = delay_by_kind.get(kind, 0.0) + delay - t0.get(tid, (name, 0.0, 0.0))[2]
worker_delay_ns = delay_by_kind.get("stream_worker", 0.0)
threads_ms = {k: v / ticks * 1000.0 / processed for k, v in by_kind.items()} if processed else None
# The same run-queue wait for every kind of thread: the receive threads' ("other") is time a
# scan waited before its arrival was stamped, which the latency does not include.
threads_delay_ms = {k: v * 1e-6 / processed for k, v in delay_by_kind.items()} if processed else None
# PIN=1: how busy the daemon's core was with other processes (its busy time minus the daemon's
# CPU, over the wall time), and how long the workers waited for the core while they had a frame
# to run (schedstat run delay: behind other processes or the daemon's own threads).
core_start, core_end = float(sys.argv[13]), float(sys.argv[14])
other_load = ((core_end - core_start) - (cpu_end - cpu_start)) / ticks / (end - start) \
    if core_end > 0 else None
# End to end: each odometry's reception at the probe (system clock) minus its scan's slot in
# the replay's schedule (logged by litamin2-replay: first slot, period, stagger), so the wait of
# a scan before the daemon's receive thread takes it is included (the daemon's latency starts
# after the conversion). Stream bench_k is the replay's stream k-1; the frame's index is its
# stamp's line in seq/times.txt (FRAME_SHIFT: in seq_long/times.txt, less the stream's first frame).
e2e_p50 = e2e_p99_worst = e2e_p99_all = None
# The same from frame STEADY_FROM (default 20: 2 s at 10 Hz) on, after the start, where every
# stream's first scans (the map begun, the second scan's starts at speed) arrive at once.
steady_from = int(os.environ.get("STEADY_FROM", "20"))
e2e_steady_p50 = e2e_steady_p99 = e2e_steady_p99_worst = None
sched = None
# The replay's own lateness (its core taken from it): the latest write's start after its slot,
# and the writes that started over 5 ms late, over all streams.
replay_late_ms, replay_late_writes = None, 0
for line in open(out + "/replay.log"):
    m = re.search(r"latest start ([\d.]+) ms after its slot, (\d+) over 5 ms", line)
    if m:
        replay_late_ms = max(replay_late_ms or 0.0, float(m.group(1)))
        replay_late_writes += int(m.group(2))
for line in open(out + "/replay.log"):
    m = re.search(r"schedule: first slot ([\d.]+) s since the epoch, period (\d+) ns, stagger (on|off)", line)
    if m: sched = (float(m.group(1)), int(m.group(2)), m.group(3) == "on")
# FRAME_SHIFT=S: stream k's scans start at frame (k-1)*S of seq_long, whose stamps they keep.
frame_shift = int(os.environ.get("FRAME_SHIFT", "0"))
times = "seq_long/times.txt" if frame_shift > 0 else "seq/times.txt"
if sched and os.path.exists(times):
    first, period_ns, stagger = sched
    index = {round(float(t) * 1e6): i for i, t in enumerate(open(times).read().split())}
    all_ms, worst, steady_ms, steady_worst = [], [], [], []
    for k in range(1, n + 1):
        path = f"{out}/arrivals_bench_{k}.txt"
        if not os.path.exists(path): continue
        offset_ns = (k - 1) * period_ns // n if stagger else 0
        ms, steady = [], []
        for line in open(path):
            recv, stamp = line.split()[:2]
            sec, nsec = stamp.split(".")
            i = index.get(round((int(sec) + int(nsec) * 1e-9) * 1e6))
            if i is None: continue
            i -= (k - 1) * frame_shift
            ms.append((float(recv) - first - (offset_ns + i * period_ns) * 1e-9) * 1000.0)
            if i >= steady_from: steady.append(ms[-1])
        if ms:
            ms.sort(); all_ms += ms
            worst.append(ms[min(len(ms) - 1, int(0.99 * len(ms)))])
        if steady:
            steady.sort(); steady_ms += steady
            steady_worst.append(steady[min(len(steady) - 1, int(0.99 * len(steady)))])
    if steady_ms:
        steady_ms.sort()
        e2e_steady_p50 = steady_ms[len(steady_ms) // 2]
        e2e_steady_p99 = steady_ms[min(len(steady_ms) - 1, int(0.99 * len(steady_ms)))]
        e2e_steady_p99_worst = max(steady_worst)
    if all_ms:
        all_ms.sort()
        e2e_p50 = all_ms[len(all_ms) // 2]
        e2e_p99_all = all_ms[min(len(all_ms) - 1, int(0.99 * len(all_ms)))]
        e2e_p99_worst = max(worst)
result = {
    "streams": n, "rate_hz": rate if rate == "max" else float(rate), "points_per_scan": points,
    "frames_expected": expected, "frames_processed": processed,
    "dropped": dropped + max(0, expected - processed - dropped),
    "dropped_by_daemon": dropped,
    "probe_timed_out": probe_timed_out,
    "latency_ms_p50": sorted(p50)[len(p50) // 2] if p50 else None,
    "latency_ms_p99": max(p99) if len(p99) == n else None,
    "daemon_cpu_ms_per_frame": daemon_ms, "tracking_cpu_ms_per_frame": tracking_ms,
    "offline_cpu_ms_per_frame": offline_ms,
    "e2e_latency_ms_p50": e2e_p50, "e2e_latency_ms_p99_all_frames": e2e_p99_all,
    "steady_from_frame": steady_from, "e2e_latency_ms_p50_steady": e2e_steady_p50,
    "e2e_latency_ms_p99_steady_all_frames": e2e_steady_p99,
    "e2e_latency_ms_p99_steady_worst_stream": e2e_steady_p99_worst,
    "e2e_latency_ms_p99_worst_stream": e2e_p99_worst,
    "replay_latest_start_ms": replay_late_ms, "replay_writes_over_5ms_late": replay_late_writes,
    "dds_path_cpu_ms_per_frame": daemon_ms - tracking_ms if processed else None,
    "dds_path_share_of_tracking": (daemon_ms - tracking_ms) / tracking_ms if processed and tracking_ms > 0 else None,
    "daemon_threads_cpu_ms_per_frame": threads_ms,
    "worker_run_delay_ms_per_frame": worker_delay_ns * 1e-6 / processed if processed else None,
    "daemon_threads_run_delay_ms_per_frame": threads_delay_ms,
    "other_processes_share_of_daemon_core": other_load,
    "wall_s": end - start,
    "prefault_mb": os.environ.get("PREFAULT_MB") or "auto",
    "daemon_minor_faults_per_frame": (int(sys.argv[16]) - int(sys.argv[15])) / processed
                                     if processed else None,
    "daemon_memory_at_end": open(out + "/memory.txt").read().strip()
                            if os.path.exists(out + "/memory.txt") else None,
    "input": "plain_scan" if os.environ.get("ZERO_COPY", "0") == "1" else "pointcloud2",
    "input_reliability": "best effort" if os.environ.get("BEST_EFFORT", "0") == "1" else "reliable",
    "scheduling": os.environ.get("SCHEDULING") or "default (other)",
    "tracker": os.environ.get("TRACKER") or "default",
    "frame_shift": frame_shift,
    "daemon_prefix": os.environ.get("DAEMON_PREFIX") or None,
    "publisher_prefix": os.environ.get("PUBLISHER_PREFIX") or None,
    "sched_rt_runtime_us_of_period": [int(open("/proc/sys/kernel/sched_rt_" + k + "_us").read())
                                      for k in ("runtime", "period")],
    "core_load": ("busy loop on CPU 1, nice " + os.environ.get("CORE_LOAD_NICE", "10") +
                  ", own session (autogroup)") if os.environ.get("CORE_LOAD", "0") == "1" else None,
    "load_average_1min": float(open("/proc/loadavg").read().split()[0]),
}
json.dump(result, open(out + "/result.json", "w"), indent=1)
fmt = lambda v, f="%.2f": "-" if v is None else f % v
print(f"{n} stream(s) x {frames} frames ({points} points) at {rate}: {processed}/{expected} "
      f"processed, {result['dropped']} dropped, latency p50 {fmt(result['latency_ms_p50'], '%.1f')} ms, "
      f"worst p99 {fmt(result['latency_ms_p99'], '%.1f')} ms (slot to probe: p50 "
      f"{fmt(e2e_p50, '%.1f')}, p99 {fmt(e2e_p99_all, '%.1f')}, worst stream's p99 "
      f"{fmt(e2e_p99_worst, '%.1f')} ms); CPU per frame daemon "
      f"{fmt(daemon_ms)} ms, of it tracking {fmt(tracking_ms)} ms, DDS path "
      f"{fmt(result['dds_path_cpu_ms_per_frame'])} ms (by thread: "
      + (", ".join(f"{k} {v:.2f}" for k, v in sorted(threads_ms.items())) if threads_ms else "-")
      + f"); workers waited {fmt(result['worker_run_delay_ms_per_frame'])} ms a frame for the "
      f"core, other processes used {fmt(other_load)} of it; offline tool {offline_ms:.2f} ms a frame "
      f"(wall, 1 thread); {end - start:.2f} s")
if probe_timed_out:
    print(f"warning: the probe timed out (PROBE_TIMEOUT) before every odometry message "
          f"arrived: the latencies cover the messages received, and the "
          f"{result['dropped'] - dropped} frame(s) the daemon's last status had not "
          f"processed are counted as dropped ({dropped} dropped by the daemon)", file=sys.stderr)
PY
  echo "litamin2d memory at the end: $(cat "$dir/memory.txt")"
}

# True if run_N met the bound: every frame processed, none dropped, p99 under P99_MS.
run_passes() {
  python3 - "run_$1/result.json" "${P99_MS:-20}" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
ok = r["dropped"] == 0 and r["frames_processed"] == r["frames_expected"] and \
     r["latency_ms_p99"] is not None and r["latency_ms_p99"] < float(sys.argv[2])
sys.exit(0 if ok else 1)
PY
}

if [ "${SEARCH:-0}" != 1 ]; then
  run_once "$streams"
  [ -z "${JSON:-}" ] || cp "run_$streams/result.json" "$JSON"
  exit 0
fi

# Search: double while runs pass, then bisect between the last pass and the first failure.
rm -rf search && mkdir -p search  # no run of an earlier search in this one's JSON
good=0
bad=0
n=$streams
# One count: run up to SEARCH_TRIES times, until a run passes; every run's JSON is kept
# (search/<n>.json, then <n>_try2.json ...).
count_passes() {
  local n=$1 try
  for try in $(seq 1 "${SEARCH_TRIES:-1}"); do
    run_once "$n"
    if [ "$try" = 1 ]; then
      cp "run_$n/result.json" "search/$n.json"
    else
      cp "run_$n/result.json" "search/${n}_try$try.json"
    fi
    if run_passes "$n"; then return 0; fi
  done
  return 1
}
while :; do
  if count_passes "$n"; then
    good=$n
    n=$((n * 2))
  else
    bad=$n
    break
  fi
  [ "$n" -le "${SEARCH_MAX:-1024}" ] || break
done
while [ "$bad" -gt 0 ] && [ $((bad - good)) -gt "${SEARCH_STEP:-1}" ]; do
  n=$(((good + bad) / 2))
  if count_passes "$n"; then good=$n; else bad=$n; fi
done
echo "largest stream count with 0 dropped and p99 < ${P99_MS:-20} ms: $good (first failure: $bad)"
if [ -n "${JSON:-}" ]; then
  python3 - "$good" "$bad" "${P99_MS:-20}" search "$JSON" <<'PY'
import json, os, sys
good, bad, bound, folder, out = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), sys.argv[4], sys.argv[5]
def order(f):  # <n>.json, <n>_try<k>.json
    n, _, t = f[:-5].partition("_try")
    return int(n), int(t or 1)
runs = [json.load(open(os.path.join(folder, f))) for f in sorted(os.listdir(folder), key=order)]
json.dump({"largest_streams": good, "first_failing_streams": bad or None, "p99_bound_ms": bound,
           "runs": runs}, open(out, "w"), indent=1)
PY
fi
