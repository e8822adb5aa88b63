#!/usr/bin/env bash
# Several hosts on a private network made by this script (issue 15): three network namespaces
# joined by veth pairs to a bridge namespace, each with only its own address on 10.77.0.0/24:
#   vehicle    10.77.0.1  litamin2-replay (the fleet's scans) and litamin2d A
#   daemon2    10.77.0.2  litamin2d B
#   aggregator 10.77.0.3  litamin2-aggregator and the test's odometry subscriber (daemon_probe)
# Every participant uses a Fast DDS XML profile with UDPv4 only (no shared memory: processes
# of different "hosts" must not meet through /dev/shm), bound to its host's address, unicast
# discovery to the three addresses, no multicast locators. Everything made here (namespaces,
# processes) is removed on exit.
#
# Scenarios (SCENARIOS, default "chain"):
#   chain     one daemon (vehicle host), two streams, the aggregator across the network: every
#             odometry message arrives at the aggregator host and every keyframe is stored.
#
# Ends by printing one JSON line with the issue's keys; a value not measured by the scenarios
# run is null, with the reason in the log.
# Needs root (ip netns); exits 77 (ctest SKIP_RETURN_CODE) when namespaces cannot be made.
# Usage: multihost.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
mkdir -p "$2"
work=$(cd "$2" && pwd)
bin="$build/tools"
probe="$build/tests/integration/daemon_probe"
frames=${FRAMES:-120}
rate=${RATE:-10}
domain=${DOMAIN:-47}
scenarios=${SCENARIOS:-chain}
streams=(vehicle_00 vehicle_01)
tag="lm2mh$$"
hosts=(vehicle daemon2 aggregator)
declare -A addr=([vehicle]=10.77.0.1 [daemon2]=10.77.0.2 [aggregator]=10.77.0.3)
# The participant lease: a killed daemon is dropped by the others after at most this long.
lease_s=${LEASE_S:-2}
announce_ms=${ANNOUNCE_MS:-500}

log() { echo "== $*"; }
ns() { echo "${tag}_$1"; }
in_ns() {  # in_ns HOST COMMAND...
  local host=$1
  shift
  ip netns exec "$(ns "$host")" "$@"
}

pids=()
cleanup() {
  local p
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
  for h in "${hosts[@]}" bridge; do ip netns delete "$(ns "$h")" 2>/dev/null || true; done
}
trap cleanup EXIT

if ! ip netns add "$(ns bridge)" 2>/dev/null; then
  echo "multihost: cannot create network namespaces (needs root and ip netns): skipped"
  exit 77
fi
log "network: namespaces $(ns bridge) + ${hosts[*]}, bridge br0, addresses ${addr[*]}"
ip -n "$(ns bridge)" link add br0 type bridge
ip -n "$(ns bridge)" link set br0 up
ip -n "$(ns bridge)" link set lo up
for h in "${hosts[@]}"; do
  ip netns add "$(ns "$h")"
  ip -n "$(ns bridge)" link add "p_$h" type veth peer name eth0 netns "$(ns "$h")"
  ip -n "$(ns bridge)" link set "p_$h" master br0 up
  ip -n "$(ns "$h")" link set lo up
  ip -n "$(ns "$h")" addr add "${addr[$h]}/24" dev eth0
  ip -n "$(ns "$h")" link set eth0 up
done
# The aggregator host's end of its link, for the link-cut scenario.
agg_link="p_aggregator"
for h in "${hosts[@]}"; do
  for _ in $(seq 1 20); do
    ip -n "$(ns "$h")" link show eth0 | grep -q LOWER_UP && break
    sleep 0.1
  done
  ip -n "$(ns "$h")" link show eth0 | grep -q LOWER_UP || { echo "multihost: $h's link is down"; exit 1; }
done

profile_xml() {  # profile_xml HOST > FILE
  local own=${addr[$1]} peers="" h
  for h in "${hosts[@]}"; do
    peers+="<locator><udpv4><address>${addr[$h]}</address></udpv4></locator>"
  done
  cat <<XML
<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>udp_$1</transport_id>
        <type>UDPv4</type>
        <sendBufferSize>4194304</sendBufferSize>
        <receiveBufferSize>4194304</receiveBufferSize>
        <maxInitialPeersRange>8</maxInitialPeersRange>
        <interfaceWhiteList><address>$own</address></interfaceWhiteList>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="litamin2">
      <rtps>
        <useBuiltinTransports>false</useBuiltinTransports>
        <userTransports><transport_id>udp_$1</transport_id></userTransports>
        <sendSocketBufferSize>4194304</sendSocketBufferSize>
        <listenSocketBufferSize>4194304</listenSocketBufferSize>
        <builtin>
          <discovery_config>
            <leaseDuration><sec>$lease_s</sec></leaseDuration>
            <leaseAnnouncement><sec>0</sec><nanosec>$((announce_ms * 1000000))</nanosec></leaseAnnouncement>
          </discovery_config>
          <metatrafficUnicastLocatorList>
            <locator><udpv4><address>$own</address></udpv4></locator>
          </metatrafficUnicastLocatorList>
          <initialPeersList>$peers</initialPeersList>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
XML
}

cd "$work"
for h in "${hosts[@]}"; do profile_xml "$h" > "$h.xml"; done

log "simulating ${#streams[@]} vehicles x $frames frames ($work/fleet)"
if [ ! -f "fleet/.frames_$frames" ]; then
  rm -rf fleet
  "$bin/sim/litamin2-sim" --builtin loop --fleet ${#streams[@]} --frames 0:"$frames" \
    --output fleet 2> sim.log || { cat sim.log; exit 1; }
  touch "fleet/.frames_$frames"
fi

daemon_yaml() {  # daemon_yaml HOST [EXTRA YAML LINES] > FILE
  cat <<YAML
dds: {domain: $domain, profile: xml, xml_file: $work/$1.xml, xml_profile: litamin2}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 1
queue_depth: 100
outputs: {status_period_s: 0.5}
${2:-}
YAML
}

start() {  # start HOST LOG COMMAND...: runs in HOST's namespace in the background; sets $last_pid
  local host=$1 out=$2
  shift 2
  # Not through in_ns: $! must be the process itself (ip netns exec execs it), for kill.
  ip netns exec "$(ns "$host")" "$@" > "$out" 2>&1 &
  last_pid=$!
  pids+=("$last_pid")
}

stop() {  # stop PID: SIGTERM and wait; returns the exit status
  local rc=0
  kill -TERM "$1" 2>/dev/null || true
  wait "$1" || rc=$?
  return $rc
}

stored_keyframes() {  # stored_keyframes DB [STREAM]
  local where=""
  [ -n "${2:-}" ] && where=" where stream = '$2'"
  sqlite3 -readonly "$1" "select count(*) from keyframes$where" 2>/dev/null || echo 0
}

start_aggregator() {  # start_aggregator DIR: sets $aggregator_pid
  mkdir -p "$1"
  cat > "$1/aggregator.yaml" <<YAML
dds: {domain: $domain, profile: xml, xml_file: $work/aggregator.xml, xml_profile: litamin2}
store: {path: $1/aggregator.db}
watchdog: {enabled: false}
YAML
  rm -f "$1"/aggregator.db*
  start aggregator "$1/aggregator.log" "$bin/aggregator/litamin2-aggregator" \
    --config "$1/aggregator.yaml"
  aggregator_pid=$last_pid
}

start_probe() {  # start_probe DIR TIMEOUT: sets $probe_pid; waits until its readers matched
  local args=() s
  for s in "${streams[@]}"; do args+=(--stream "$s"); done
  rm -f "$1/probe.ready"
  start aggregator "$1/probe.log" "$probe" --domain "$domain" --profile "$work/aggregator.xml" \
    --expect "$frames" --timeout "$2" --ready-file "$1/probe.ready" --arrivals-out "$1/arrivals_" \
    --poses-out "$1/received_" "${args[@]}"
  probe_pid=$last_pid
}

replay() {  # replay DIR: the fleet at $rate Hz from the vehicle host (foreground)
  local args=() s
  for s in "${streams[@]}"; do args+=(--stream "$s"); done
  in_ns vehicle "$bin/replay/litamin2-replay" --domain "$domain" --profile "$work/vehicle.xml" \
    --rate "$rate" --timeout 60 --start-delay 2 "${args[@]}" \
    $(for s in "${streams[@]}"; do echo "fleet/$s"; done) > "$1/replay.log" 2>&1
}

wait_stored() {  # wait_stored DB COUNT SECONDS: prints the count stored
  local n=0
  for _ in $(seq 1 $((${3} * 2))); do
    n=$(stored_keyframes "$1")
    [ "$n" -ge "$2" ] && break
    sleep 0.5
  done
  echo "$n"
}

status_keyframes() {  # status_keyframes PROBE_LOG: keyframes the daemons reported, summed
  grep -o 'keyframes [0-9]*' "$1" | awk '{s += $2} END {print s + 0}'
}

failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# JSON values (null until measured) and why they are null.
declare -A result=([failover_standby_s]=null [failover_reshard_s]=null
  [keyframes_published]=null [keyframes_stored]=null [keyframes_lost_link_cut]=null
  [daemon_rss_growth_mb_outage]=null)
declare -A why_null=(
  [failover_standby_s]="hot standby (EXCLUSIVE ownership) is not implemented"
  [failover_reshard_s]="the failover scenario was not run"
  [keyframes_published]="the link-cut scenario was not run"
  [keyframes_stored]="the link-cut scenario was not run"
  [keyframes_lost_link_cut]="the link-cut scenario was not run"
  [daemon_rss_growth_mb_outage]="the link-cut scenario was not run")

scenario_chain() {
  local dir="$work/chain"
  rm -rf "$dir"
  mkdir -p "$dir"
  log "chain: litamin2d on the vehicle host, aggregator and probe on the aggregator host"
  start_aggregator "$dir"
  daemon_yaml vehicle > "$dir/daemon.yaml"
  start vehicle "$dir/daemon.log" "$bin/litamin2d/litamin2d" --config "$dir/daemon.yaml"
  local daemon_pid=$last_pid
  start_probe "$dir" 120
  replay "$dir" || { cat "$dir/replay.log"; fail "chain: replay failed"; return; }
  local probe_rc=0
  wait "$probe_pid" || probe_rc=$?
  stop "$daemon_pid" || fail "chain: litamin2d exited with an error"
  local published stored
  published=$(status_keyframes "$dir/probe.log")
  stored=$(wait_stored "$dir/aggregator.db" "$published" 30)
  stop "$aggregator_pid" || fail "chain: the aggregator exited with an error"
  sed 's/^/  /' "$dir/probe.log" | grep -E "^  (stream|status)"
  echo "  chain: $published keyframes published, $stored stored"
  [ "$probe_rc" -eq 0 ] || fail "chain: the probe did not receive every odometry message in order"
  [ "$published" -gt 0 ] && [ "$stored" -eq "$published" ] ||
    fail "chain: $stored of $published keyframes stored"
}

for s in $scenarios; do "scenario_$s"; done

json="{"
for k in failover_standby_s failover_reshard_s keyframes_published keyframes_stored \
  keyframes_lost_link_cut daemon_rss_growth_mb_outage; do
  [ "${result[$k]}" = null ] && echo "  $k: null (${why_null[$k]})"
  json+="\"$k\": ${result[$k]}, "
done
json="${json%, }}"
echo "$json"
[ "$failures" -eq 0 ] || { echo "multihost FAILED ($failures failure(s))"; exit 1; }
echo "multihost OK"
