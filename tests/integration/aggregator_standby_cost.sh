#!/usr/bin/env bash
# What the aggregator's hot standby costs (not a ctest; issue 15's "extra CPU and traffic of
# k = 2"): the same map patches ingested by one litamin2-aggregator (k = 1, standby.strength 2)
# and by two (k = 2: strengths 2 and 1, each with its own store), in alternating runs (k = 1,
# k = 2, k = 1, ...: RUNS of each) so that the machine's other load falls on both alike.
# Workload: aggregator_probe publish --synthetic DISTRIBUTIONS --streams-count STREAMS at one
# patch per second per stream for DURATION s (SCENE=1, the default: each stream drives through
# its own scene, as in aggregator_bench.sh), with the readers a deployment has: an exclusive
# keyframe-poses reader (aggregator_probe poses --exclusive) and an exclusive map-tiles reader
# (litamin2-map-tiles --exclusive). In a private network namespace (unshare -n, only lo up)
# with a UDP-only profile on 127.0.0.1 (no shared memory: every byte between the processes
# crosses lo, as it would cross the network between hosts; unicast discovery, no multicast).
# Per run, over the window from the first patch to the aggregators going quiet (CPU below 2 %
# of a core for 1 s): each aggregator's CPU (utime + stime, /proc/PID/stat), the publisher's
# CPU, and lo's tx packets and bytes (/proc/net/dev: every datagram between
# the processes, counted once); the keyframes each store holds at the end.
# Also the UDP payload per sender -> receiver (tcpdump of lo's headers; each port attributed to
# its process with ss -ulpn). Prints one line per run and a JSON line per run ("k",
# "aggregator_cpu_s", ...).
# Usage: aggregator_standby_cost.sh BUILD_DIR WORK_DIR (env STREAMS=10 DISTRIBUTIONS=3000
#   DURATION=30 RUNS=2 SCENE=1)
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/traffic_counters.sh"
build=$(cd "$1" && pwd)
work=$2
aggregator=$build/tools/aggregator/litamin2-aggregator
probe=$build/tests/integration/aggregator_probe
tiles_client=$build/tools/map_tiles/litamin2-map-tiles
streams=${STREAMS:-10}
distributions=${DISTRIBUTIONS:-3000}
duration=${DURATION:-30}
runs=${RUNS:-2}
scene=--scene
[ "${SCENE:-1}" = 1 ] || scene=
domain=46
rm -rf "$work"
mkdir -p "$work"
cd "$work"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

write_udp_lo_profile udp_lo.xml
profile=$PWD/udp_lo.xml:litamin2

one_run() {  # one_run K RUN
  local k=$1 dir="k$1_run$2" names=(a) strengths=(2) p
  [ "$k" -eq 2 ] && names=(a b) && strengths=(2 1)
  mkdir -p "$dir"
  local agg_pids=() i
  for i in "${!names[@]}"; do
    cat > "$dir/${names[$i]}.yaml" <<YAML
dds: {domain: $domain, profile: xml, xml_file: $PWD/udp_lo.xml, xml_profile: litamin2}
store: {path: $PWD/$dir/${names[$i]}.db}
standby: {strength: ${strengths[$i]}}
YAML
    "$aggregator" --config "$dir/${names[$i]}.yaml" > "$dir/${names[$i]}.log" 2>&1 &
    agg_pids+=("$!")
    pids+=("$!")
  done
  for i in "${!names[@]}"; do
    for _ in $(seq 1 200); do
      grep -q "DDS participant up" "$dir/${names[$i]}.log" 2>/dev/null && break
      sleep 0.05
    done
  done
  local stream_args=() s
  for s in $(seq 0 $((streams - 1))); do stream_args+=(--stream "$(printf 's%03d' "$s")"); done
  "$probe" --domain $domain --profile "$profile" poses --exclusive --expect 1000000 \
    --timeout $((duration + 120)) "${stream_args[@]}" > "$dir/poses.log" 2>&1 &
  local poses_pid=$!
  pids+=("$poses_pid")
  "$tiles_client" --domain $domain --profile "$profile" --exclusive --count 100000000 \
    --timeout $((duration + 120)) > "$dir/tiles.log" 2>&1 &
  local tiles_pid=$!
  pids+=("$tiles_pid")
  sleep 2  # discovery
  local c0=() c1=() t0 t1 pk0 by0 pk1 by1 pub_cpu
  # The datagrams' headers on lo (tcpdump), and which process owns which UDP port (ss, a few
  # seconds into the publishing, when every socket exists): the bytes per sender -> receiver.
  tcpdump -i lo -nn -q -s 96 -w "$dir/lo.pcap" udp > "$dir/tcpdump.log" 2>&1 &
  local tcpdump_pid=$!
  pids+=("$tcpdump_pid")
  (sleep 5; ss -ulpn > "$dir/sockets.txt") &
  local ss_pid=$!
  sleep 1
  for p in "${agg_pids[@]}"; do c0+=("$(ticks "$p")"); done
  pk0=$(lo tx_packets)
  by0=$(lo tx_bytes)
  t0=$(date +%s.%N)
  # The publisher in a subshell whose `times` gives its CPU (the children's line).
  (
    rc=0
    "$probe" --domain $domain --profile "$profile" publish --synthetic "$distributions" \
      --streams-count "$streams" --rate 1 $scene --duration "$duration" --linger 2 \
      > "$dir/publish.log" 2>&1 || rc=$?
    times > "$dir/publish.times"
    exit $rc
  ) || { cat "$dir/publish.log"; echo "publisher failed"; exit 1; }
  pub_cpu=$(children_cpu_s "$dir/publish.times")
  # Until every aggregator is quiet (under 2 % of a core for 1 s).
  wait_quiet 600 "${agg_pids[@]}"
  for p in "${agg_pids[@]}"; do c1+=("$(ticks "$p")"); done
  pk1=$(lo tx_packets)
  by1=$(lo tx_bytes)
  t1=$(date +%s.%N)
  kill -INT "$tcpdump_pid" 2>/dev/null || true
  wait "$tcpdump_pid" 2>/dev/null || true
  wait "$ss_pid" || true
  local roles
  roles="${agg_pids[0]}=aggregator_A $poses_pid=poses_reader $tiles_pid=tiles_reader"
  [ "$k" -eq 2 ] && roles+=" ${agg_pids[1]}=aggregator_B"
  traffic_matrix "$dir" "$roles" > "$dir/traffic.txt"
  kill -TERM "$poses_pid" "$tiles_pid" 2>/dev/null || true
  wait "$poses_pid" 2>/dev/null || true
  wait "$tiles_pid" 2>/dev/null || true
  local cpu_each=() total=0 stored=()
  for i in "${!agg_pids[@]}"; do
    kill -TERM "${agg_pids[$i]}"
    wait "${agg_pids[$i]}" || { echo "aggregator ${names[$i]} exited with an error"; exit 1; }
    cpu_each+=("$(echo "scale=2; (${c1[$i]} - ${c0[$i]}) / $hz" | bc)")
    total=$((total + c1[i] - c0[i]))
    stored+=("$(sqlite3 -readonly "$dir/${names[$i]}.db" 'select count(*) from keyframes')")
  done
  local wall cpu mb
  wall=$(echo "$t1 - $t0" | bc -l | awk '{printf "%.1f", $1}')
  cpu=$(echo "scale=2; $total / $hz" | bc)
  mb=$(echo "($by1 - $by0) / 1000000" | bc -l | awk '{printf "%.1f", $1}')
  sed "s/^/  /" "$dir/traffic.txt"
  echo "k=$k run $2: aggregator CPU ${cpu} s (${cpu_each[*]}) over ${wall} s; publisher CPU" \
    "$pub_cpu s; lo $((pk1 - pk0)) datagrams, $mb MB; keyframes stored ${stored[*]}"
  printf '{"k": %d, "run": %d, "aggregator_cpu_s": %s, "publisher_cpu_s": %s, "window_s": %s, "lo_datagrams": %d, "lo_mb": %s, "stored": "%s"}\n' \
    "$k" "$2" "$cpu" "$pub_cpu" "$wall" $((pk1 - pk0)) "$mb" "${stored[*]}" >> results.jsonl
}

echo "== $streams streams x 1 patch/s x $distributions distributions${scene:+ (scene)}, $duration s; k = 1 and 2 alternating, $runs runs each"
for run in $(seq 1 "$runs"); do
  one_run 1 "$run"
  one_run 2 "$run"
done
cat results.jsonl
