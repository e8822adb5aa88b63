#!/usr/bin/env bash
# What litamin2d's hot standby costs (not a ctest; issue 15's "extra CPU and traffic of k = 2"):
# the same scans tracked by one litamin2d (k = 1: sharding with replicas 1, one member) and by
# two (k = 2: sharding.replicas 2, members daemon-a and daemon-b, each tracking every stream;
# the odometry written with EXCLUSIVE ownership, the standby's map patches held), in
# alternating runs (k = 1, k = 2, k = 1, ...: RUNS of each) so that the machine's other load
# falls on both alike.
# Workload: STREAMS simulated vehicles (litamin2-sim --builtin loop --fleet, FRAMES frames each)
# published by litamin2-replay at RATE Hz per stream, with the readers a deployment has: the
# odometry and status reader (daemon_probe; --exclusive for k = 2) and litamin2-aggregator
# (ingest.exclusive_odometry for k = 2). In a private network namespace (unshare -n, only lo
# up) with a UDP-only profile on 127.0.0.1 (no shared memory: every byte between the processes
# crosses lo, as it would cross the network between hosts; unicast discovery, no multicast).
# Per run, over the window from the replay's start to the daemons going quiet (CPU below 2 % of
# a core for 1 s) after it ended: each litamin2d's CPU (utime + stime, /proc/PID/stat), the
# replay's CPU, lo's tx packets and bytes (/proc/net/dev: every datagram between the processes,
# counted once), the UDP payload per sender -> receiver (tcpdump of lo's headers; each port
# attributed to its process with ss -ulpn), the keyframes the aggregator stored.
# Prints one line per run and a JSON line per run ("k", "daemon_cpu_s", ...).
# Usage: daemon_standby_cost.sh BUILD_DIR WORK_DIR (env STREAMS=4 FRAMES=150 RATE=10 RUNS=2)
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/traffic_counters.sh"
build=$(cd "$1" && pwd)
work=$2
daemon=$build/tools/litamin2d/litamin2d
aggregator=$build/tools/aggregator/litamin2-aggregator
replay=$build/tools/replay/litamin2-replay
sim=$build/tools/sim/litamin2-sim
probe=$build/tests/integration/daemon_probe
streams=${STREAMS:-4}
frames=${FRAMES:-150}
rate=${RATE:-10}
runs=${RUNS:-2}
domain=48
rm -rf "$work"
mkdir -p "$work"
cd "$work"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

write_udp_lo_profile udp_lo.xml 2
profile=$PWD/udp_lo.xml

echo "== simulating $streams vehicles x $frames frames"
"$sim" --builtin loop --fleet "$streams" --frames 0:"$frames" --output fleet > sim.log 2>&1 ||
  { cat sim.log; exit 1; }
stream_ids=()
for s in $(seq 0 $((streams - 1))); do stream_ids+=("$(printf 'vehicle_%02d' "$s")"); done

one_run() {  # one_run K RUN
  local k=$1 dir="k$1_run$2" names=(a) p i
  [ "$k" -eq 2 ] && names=(a b)
  mkdir -p "$dir"
  local daemon_pids=()
  for i in "${!names[@]}"; do
    cat > "$dir/daemon_${names[$i]}.yaml" <<YAML
dds: {domain: $domain, profile: xml, xml_file: $profile, xml_profile: litamin2}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 1
queue_depth: 100
outputs: {status_period_s: 0.5}
member_id: daemon-${names[$i]}
sharding: {enabled: true, startup_wait_s: 3, replicas: $k}
YAML
    "$daemon" --config "$dir/daemon_${names[$i]}.yaml" > "$dir/daemon_${names[$i]}.log" 2>&1 &
    daemon_pids+=("$!")
    pids+=("$!")
  done
  local exclusive=() ingest=""
  if [ "$k" -eq 2 ]; then
    exclusive=(--exclusive)
    ingest="ingest: {exclusive_odometry: true}"
  fi
  cat > "$dir/aggregator.yaml" <<YAML
dds: {domain: $domain, profile: xml, xml_file: $profile, xml_profile: litamin2}
store: {path: $PWD/$dir/aggregator.db}
watchdog: {enabled: false}
$ingest
YAML
  "$aggregator" --config "$dir/aggregator.yaml" > "$dir/aggregator.log" 2>&1 &
  local aggregator_pid=$!
  pids+=("$aggregator_pid")
  local probe_args=() s
  for s in "${stream_ids[@]}"; do probe_args+=(--stream "$s"); done
  "$probe" --domain $domain --profile "$profile" --expect "$frames" --timeout $((frames / rate + 60)) \
    "${exclusive[@]}" "${probe_args[@]}" > "$dir/probe.log" 2>&1 &
  local probe_pid=$!
  pids+=("$probe_pid")
  sleep 2  # discovery
  tcpdump -i lo -nn -q -s 96 -w "$dir/lo.pcap" udp > "$dir/tcpdump.log" 2>&1 &
  local tcpdump_pid=$!
  pids+=("$tcpdump_pid")
  (sleep 8; ss -ulpn > "$dir/sockets.txt") &
  local ss_pid=$!
  sleep 1
  local c0=() c1=() t0 t1 pk0 by0 pk1 by1 replay_cpu
  for p in "${daemon_pids[@]}"; do c0+=("$(ticks "$p")"); done
  pk0=$(lo tx_packets)
  by0=$(lo tx_bytes)
  t0=$(date +%s.%N)
  # The replay in a subshell whose `times` gives its CPU (the children's line). Each stream
  # waits for k readers (the daemons), then 4 s for the sharding (startup_wait_s 3) to settle.
  (
    rc=0
    "$replay" --domain $domain --profile "$profile" --rate "$rate" --timeout 60 \
      --wait-subscribers "$k" --start-delay 4 \
      $(for s in "${stream_ids[@]}"; do echo "--stream $s"; done) \
      $(for s in "${stream_ids[@]}"; do echo "fleet/$s"; done) > "$dir/replay.log" 2>&1 || rc=$?
    times > "$dir/replay.times"
    exit $rc
  ) || { cat "$dir/replay.log"; echo "replay failed"; exit 1; }
  replay_cpu=$(children_cpu_s "$dir/replay.times")
  # Until every daemon is quiet (under 2 % of a core for 1 s).
  wait_quiet 120 "${daemon_pids[@]}"
  for p in "${daemon_pids[@]}"; do c1+=("$(ticks "$p")"); done
  pk1=$(lo tx_packets)
  by1=$(lo tx_bytes)
  t1=$(date +%s.%N)
  kill -INT "$tcpdump_pid" 2>/dev/null || true
  wait "$tcpdump_pid" 2>/dev/null || true
  wait "$ss_pid" || true
  local roles="${daemon_pids[0]}=daemon_A $aggregator_pid=aggregator $probe_pid=probe"
  [ "$k" -eq 2 ] && roles+=" ${daemon_pids[1]}=daemon_B"
  traffic_matrix "$dir" "$roles" replay > "$dir/traffic.txt"
  # Every stream's odometry must arrive. k = 2: an exclusive reader can take the first frame
  # from both writers (before the stronger one matches: docs/deploy.md, "Hot standby"), which
  # the probe's order check rejects ("message 1 is not after message 0"): counted, not failed.
  local probe_rc=0 short
  wait "$probe_pid" || probe_rc=$?
  short=$(awk -v n="$frames" '/odometry message\(s\), expected/ && $3 < n' "$dir/probe.log")
  if [ -n "$short" ] || { [ "$probe_rc" -ne 0 ] && [ "$k" -eq 1 ]; } ||
    grep "^stream .*: message" "$dir/probe.log" | grep -qv "message 1 is not after message 0"; then
    cat "$dir/probe.log"
    echo "k=$k: the probe did not get every odometry message in order"
    exit 1
  fi
  local repeated
  repeated=$(grep -c "message 1 is not after message 0" "$dir/probe.log" || true)
  local cpu_each=() total=0 tracked=() owned=()
  for i in "${!daemon_pids[@]}"; do
    kill -TERM "${daemon_pids[$i]}"
    wait "${daemon_pids[$i]}" || { echo "litamin2d ${names[$i]} exited with an error"; exit 1; }
    cpu_each+=("$(echo "scale=2; (${c1[$i]} - ${c0[$i]}) / $hz" | bc)")
    total=$((total + c1[i] - c0[i]))
    # At the start (the log's later lines include the handover at the other's SIGTERM).
    tracked+=("$(grep -c ': tracked here' "$dir/daemon_${names[$i]}.log" || true)")
    owned+=("$(grep -c ': owned here (strength' "$dir/daemon_${names[$i]}.log" || true)")
  done
  kill -TERM "$aggregator_pid"
  wait "$aggregator_pid" || { echo "the aggregator exited with an error"; exit 1; }
  local stored published
  stored=$(sqlite3 -readonly "$dir/aggregator.db" 'select count(*) from keyframes')
  published=$(grep -o 'keyframes [0-9]*' "$dir/probe.log" | awk '{s += $2} END {print s + 0}')
  local wall cpu mb
  wall=$(echo "$t1 - $t0" | bc -l | awk '{printf "%.1f", $1}')
  cpu=$(echo "scale=2; $total / $hz" | bc)
  mb=$(echo "($by1 - $by0) / 1000000" | bc -l | awk '{printf "%.1f", $1}')
  sed "s/^/  /" "$dir/traffic.txt"
  echo "k=$k run $2: litamin2d CPU ${cpu} s (${cpu_each[*]}; streams tracked ${tracked[*]}, owned ${owned[*]}) over" \
    "${wall} s; replay CPU $replay_cpu s; lo $((pk1 - pk0)) datagrams, $mb MB;" \
    "keyframes published $published, stored $stored; first frame twice: $repeated stream(s)"
  printf '{"k": %d, "run": %d, "daemon_cpu_s": %s, "daemon_cpu_each_s": "%s", "replay_cpu_s": %s, "window_s": %s, "lo_datagrams": %d, "lo_mb": %s, "published": %d, "stored": %d}\n' \
    "$k" "$2" "$cpu" "${cpu_each[*]}" "$replay_cpu" "$wall" $((pk1 - pk0)) "$mb" "$published" \
    "$stored" >> results.jsonl
}

echo "== $streams streams x $frames frames at $rate Hz; k = 1 and 2 alternating, $runs runs each"
for run in $(seq 1 "$runs"); do
  one_run 1 "$run"
  one_run 2 "$run"
done
cat results.jsonl
