#!/usr/bin/env bash
# Packet loss on the daemon -> aggregator link during ingest (issue 15's "loss 10 %" case,
# without sch_netem): a simulated 2-vehicle fleet -> litamin2-replay -> litamin2d ->
# litamin2-aggregator, twice, inside a private network namespace (loopback-only UDP profile,
# unicast discovery, no multicast; nothing leaves the machine):
#   baseline  litamin2d and the aggregator with LITAMIN2_TEST_UDP_LOSS_PERCENT=0: the same
#             UDP-only transports (no shared memory) with nothing dropped;
#   lossy     both with LITAMIN2_TEST_UDP_LOSS_PERCENT=$LOSS (default 10): each drops LOSS % of
#             the DATA, DATA_FRAG, HEARTBEAT and ACKNACK messages it sends (Fast DDS's
#             test_UDPv4Transport drops at send, so both ends of the link are lossy:
#             patches and heartbeats one way, acknacks the other; the daemon's odometry and
#             status to the probe are lossy too). No delay is emulated.
#   lossy_early_stop  (with EARLY_STOP=1) the same, with litamin2d sent SIGTERM as soon as the probe has the last
#             odometry message (not when the aggregator has stored everything): its shutdown
#             waits, within shutdown_timeout_s, for the patches still being resent.
# Checked in each run: the services' UDP sockets are all on 127.0.0.1 (a veth with 10.99.0.1 is
# added to the namespace to make that meaningful), every odometry message reaches the probe (reliable), the aggregator stores
# every keyframe the daemon reported (0 lost), per stream with ids 0..n-1 and no duplicates,
# within INGEST_BOUND_S (default 30 s) after the replay's last scan; every process exits 0.
# Measured: ingest lag (last scan sent -> last keyframe stored, polled every 0.1 s once the probe
# has every odometry message; litamin2d stays up until then), UDP datagrams sent in the
# namespace (/proc/net/snmp; the retransmissions' cost shows as the difference to the baseline;
# dropped messages are never handed to the kernel). Prints one JSON line.
# Usage: lossy_link.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$(cd "$1" && pwd)
mkdir -p "$2"
work=$(cd "$2" && pwd)
bin=$build/tools
probe=$build/tests/integration/daemon_probe
frames=${FRAMES:-60}
rate=${RATE:-10}
loss=${LOSS:-10}
bound=${INGEST_BOUND_S:-30}
streams=(vehicle_00 vehicle_01)
cd "$work"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

echo "== simulating ${#streams[@]} vehicles x $frames frames"
rm -rf fleet
"$bin/sim/litamin2-sim" --builtin loop --fleet ${#streams[@]} --frames 0:"$frames" \
  --output fleet 2> sim.log || { cat sim.log; exit 1; }

# A second interface with another address in the namespace, so that the check that the lossy
# transports keep the loopback profile's whitelist (sockets on 127.0.0.1 only) means something.
other_if=0
if ip link add lossy0 type veth peer name lossy1 2> /dev/null; then
  ip addr add 10.99.0.1/24 dev lossy0 && ip link set lossy0 up && ip link set lossy1 up && other_if=1
fi
sockets() {  # sockets PID: local addresses of its UDP sockets
  ss -uanp | awk -v p="pid=$1," 'index($0, p) {print $4}' | sort -u
}

udp_out() { awk '/^Udp:/ { if (++n == 2) print $5 }' /proc/net/snmp; }  # OutDatagrams
stored() { sqlite3 -readonly "$1" "select count(*) from keyframes" 2>/dev/null || echo 0; }

declare -A result
run() {  # run NAME LOSS_PERCENT DOMAIN [early]
  local name=$1 percent=$2 domain=$3 dir="$work/$1" early=${4:-}
  rm -rf "$dir"
  mkdir -p "$dir"
  echo "== $name: litamin2d and the aggregator with LITAMIN2_TEST_UDP_LOSS_PERCENT=$percent"
  cat > "$dir/aggregator.yaml" <<YAML
dds: {domain: $domain, profile: loopback}
store: {path: $dir/aggregator.db}
watchdog: {enabled: false}
YAML
  cat > "$dir/daemon.yaml" <<YAML
dds: {domain: $domain, profile: loopback}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 1
queue_depth: 100
outputs: {status_period_s: 0.5}
YAML
  local udp0 t0
  udp0=$(udp_out)
  t0=$(date +%s.%N)
  LITAMIN2_TEST_UDP_LOSS_PERCENT=$percent "$bin/aggregator/litamin2-aggregator" \
    --config "$dir/aggregator.yaml" > "$dir/aggregator.log" 2>&1 &
  local aggregator_pid=$!
  LITAMIN2_TEST_UDP_LOSS_PERCENT=$percent "$bin/litamin2d/litamin2d" \
    --config "$dir/daemon.yaml" > "$dir/daemon.log" 2>&1 &
  local daemon_pid=$!
  pids+=("$aggregator_pid" "$daemon_pid")
  local args=() s
  for s in "${streams[@]}"; do args+=(--stream "$s"); done
  "$probe" --domain "$domain" --expect "$frames" --timeout $((frames / rate + 60)) \
    "${args[@]}" > "$dir/probe.log" 2>&1 &
  local probe_pid=$!
  pids+=("$probe_pid")
  # Once the participants are up: every UDP socket of both services on 127.0.0.1.
  for _ in $(seq 1 50); do [ -n "$(sockets "$daemon_pid")" ] && [ -n "$(sockets "$aggregator_pid")" ] && break; sleep 0.1; done
  local elsewhere
  elsewhere=$( (sockets "$daemon_pid"; sockets "$aggregator_pid") | grep -v '^127\.0\.0\.1:' || true)
  [ -z "$elsewhere" ] || fail "$name: sockets off the loopback whitelist: $elsewhere"
  [ -n "$(sockets "$daemon_pid")" ] || fail "$name: litamin2d has no UDP socket"
  [ "$other_if" -eq 1 ] && echo "  UDP sockets: $( (sockets "$daemon_pid"; sockets "$aggregator_pid") | wc -l), all on 127.0.0.1 (10.99.0.1 also present)"
  local replay_rc=0
  timeout $((frames / rate + 60)) "$bin/replay/litamin2-replay" --domain "$domain" \
    --profile loopback --rate "$rate" --start-delay 2 "${args[@]}" \
    $(for s in "${streams[@]}"; do echo "fleet/$s"; done) > "$dir/replay.log" 2>&1 ||
    replay_rc=$?
  local replay_end
  replay_end=$(date +%s.%N)
  [ "$replay_rc" -eq 0 ] || { cat "$dir/replay.log"; fail "$name: replay failed ($replay_rc)"; }
  local probe_rc=0
  wait "$probe_pid" || probe_rc=$?
  [ "$probe_rc" -eq 0 ] || fail "$name: the probe did not get every odometry message"
  local published n=0 done_at=""
  published=$(grep -o 'keyframes [0-9]*' "$dir/probe.log" | awk '{s += $2} END {print s + 0}')
  local rc=0
  if [ -n "$early" ]; then
    # litamin2d stopped as soon as the last odometry arrived: its shutdown waits (within
    # shutdown_timeout_s) for the aggregator to acknowledge the patches still being resent.
    kill -TERM "$daemon_pid"
    wait "$daemon_pid" || rc=$?
    [ "$rc" -eq 0 ] || fail "$name: litamin2d exited with $rc"
    grep -q "not acknowledged" "$dir/daemon.log" && echo "  litamin2d: $(grep -o 'map patches.*' "$dir/daemon.log")"
  fi
  # Ingest: until every keyframe the daemon reported is stored, or the bound.
  while awk -v a="$replay_end" -v b="$(date +%s.%N)" -v m="$bound" 'BEGIN {exit !(b - a < m)}'; do
    n=$(stored "$dir/aggregator.db")
    if [ "$published" -gt 0 ] && [ "$n" -ge "$published" ]; then
      done_at=$(date +%s.%N)
      break
    fi
    sleep 0.1
  done
  n=$(stored "$dir/aggregator.db")
  if [ -z "$early" ]; then
    kill -TERM "$daemon_pid" "$aggregator_pid"
    wait "$daemon_pid" || rc=$?
    [ "$rc" -eq 0 ] || fail "$name: litamin2d exited with $rc"
  else
    kill -TERM "$aggregator_pid"
  fi
  rc=0
  wait "$aggregator_pid" || rc=$?
  [ "$rc" -eq 0 ] || fail "$name: the aggregator exited with $rc"
  local udp1 t1
  udp1=$(udp_out)
  t1=$(date +%s.%N)
  grep -E "^status " "$dir/probe.log" | sed 's/^/  /'
  sqlite3 -readonly "$dir/aggregator.db" \
    "select '  stored ' || stream || ': ' || count(*) || ' keyframes, ids ' || min(id) || '..' || max(id) || ', ' || count(distinct id) || ' distinct' from keyframes group by stream"
  local gaps
  gaps=$(sqlite3 -readonly "$dir/aggregator.db" \
    "select count(*) from (select stream from keyframes group by stream having count(*) != max(id) + 1 or count(distinct id) != count(*) or min(id) != 0)")
  [ "$gaps" -eq 0 ] || fail "$name: $gaps stream(s) with missing or duplicate keyframe ids"
  grep -q "TEST ONLY: LITAMIN2_TEST_UDP_LOSS_PERCENT=$percent" "$dir/daemon.log" ||
    fail "$name: litamin2d did not report the test transport"
  grep -q "TEST ONLY: LITAMIN2_TEST_UDP_LOSS_PERCENT=$percent" "$dir/aggregator.log" ||
    fail "$name: the aggregator did not report the test transport"
  # What the lossy transports dropped (printed by each process at exit).
  local drops
  for drops in daemon aggregator; do
    grep -h "datagrams dropped/submessages seen" "$dir/$drops.log" | sed "s/^.*seen: /  $drops dropped\/seen: /" ||
      fail "$name: $drops did not report its drop counts"
  done
  result[${name}_dropped]=$(grep -h "datagrams dropped/submessages seen" "$dir/daemon.log" "$dir/aggregator.log" |
    grep -o '[0-9]*/' | tr -d / | awk '{s += $1} END {print s + 0}')
  local lag="null"
  [ -n "$done_at" ] && lag=$(echo "$done_at - $replay_end" | bc -l | awk '{printf "%.2f", $1}')
  echo "  $name: $published keyframes published, $n stored ($((published - n)) lost);" \
    "ingest lag after the last scan ${lag} s; run $(echo "$t1 - $t0" | bc -l | awk '{printf "%.1f", $1}') s;" \
    "$((udp1 - udp0)) UDP datagrams sent in the namespace"
  [ "$percent" -eq 0 ] || [ "${result[${name}_dropped]}" -gt 0 ] ||
    fail "$name: nothing was dropped: the loss is not in effect"
  [ "$percent" -ne 0 ] || [ "${result[${name}_dropped]}" -eq 0 ] ||
    fail "$name: datagrams dropped at 0 %"
  [ "$published" -gt 0 ] && [ "$n" -eq "$published" ] ||
    fail "$name: $((published - n)) keyframe(s) lost (bound ${bound} s)"
  result[${name}_published]=$published
  result[${name}_lost]=$((published - n))
  result[${name}_lag]=$lag
  result[${name}_udp]=$((udp1 - udp0))
}

run baseline 0 48
run lossy "$loss" 49
if [ "${EARLY_STOP:-0}" = 1 ]; then run lossy_early_stop "$loss" 50 early; fi

echo "{\"loss_percent\": $loss, \"frames\": $frames, \"streams\": ${#streams[@]}," \
  "\"keyframes_published\": ${result[lossy_published]}," \
  "\"keyframes_lost_loss$loss\": ${result[lossy_lost]}," \
  "\"ingest_lag_s_loss0\": ${result[baseline_lag]}, \"ingest_lag_s_loss$loss\": ${result[lossy_lag]}," \
  "\"udp_datagrams_loss0\": ${result[baseline_udp]}, \"udp_datagrams_loss$loss\": ${result[lossy_udp]}," \
  "\"datagrams_dropped_loss0\": ${result[baseline_dropped]}, \"datagrams_dropped_loss$loss\": ${result[lossy_dropped]}," \
  "\"keyframes_lost_loss${loss}_early_stop\": ${result[lossy_early_stop_lost]:-null}}"
[ "$failures" -eq 0 ] || { echo "lossy_link FAILED ($failures failure(s))"; exit 1; }
# Passed: the simulated scans go (kept on failure for a look; CI has a disk of its own size).
rm -rf "$work/fleet"
echo "lossy_link OK"
