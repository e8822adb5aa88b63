#!/usr/bin/env bash
# DDS-Security end to end (issue 14), in a private network namespace (only lo up), UDP on
# 127.0.0.1 only (an XML profile without shared memory, so that all traffic crosses lo and is
# captured). A fleet PKI from scripts/litamin2-pki; litamin2d and litamin2-aggregator secured.
#  1. A vehicle identity replays a stream whose id holds a marker; an operator identity gets
#     every odometry message; the aggregator stores the stream's keyframes; a map client
#     identity (litamin2-map-tiles) gets the aggregator's map tiles.
#  2. Participants without a valid certificate (no security; a certificate of another CA) get
#     no odometry, and their point clouds and map patches change nothing: the daemon's streams
#     and counters and the store's rows stay as they were.
#  3. Valid participants without permission for a topic are refused: a vehicle publishing
#     another vehicle's points, a vehicle or an operator publishing map patches, a vehicle
#     reading the map patches or the map tiles.
#  4. The capture of lo holds no plaintext of the marker (discovery, metadata and data are
#     AES-GCM encrypted; the permissions name streams by pattern, see docs/security.md).
#  5. Tampered, unsigned, expired and mismatched files stop each process at start (exit 2)
#     with a message naming the key and the file.
# Usage: security.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/service_helpers.sh"
build=$1
work=$2
source_dir=$3
tools=$build/tools
probes=$build/tests/integration
pki_tool=$source_dir/scripts/litamin2-pki
frames=12
domain=53
marker=fleet_Zq7mK4marker
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
  echo "FAIL: $*"
  for f in daemon.log aggregator.log; do [ -f "$f" ] && { echo "--- $f"; tail -n 30 "$f"; }; done
  exit 1
}

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

echo "== PKI (scripts/litamin2-pki): streams granted by the pattern fleet_*"
"$pki_tool" init pki --domains $domain-$domain
"$pki_tool" vehicle pki vehicle_a --streams 'fleet_*'
"$pki_tool" vehicle pki vehicle_b --streams 'other_*'
"$pki_tool" daemon pki host_a --streams 'fleet_*'
"$pki_tool" aggregator pki aggregator
"$pki_tool" operator pki operator
"$pki_tool" map-client pki map_client
# Another fleet's CA: a certificate that is valid, but not ours.
"$pki_tool" init rogue --domains $domain-$domain > /dev/null
"$pki_tool" vehicle rogue vehicle_a --streams 'fleet_*' > /dev/null
grep -q "$marker" pki/*/permissions.xml pki/governance.xml && fail "the marker is in a grant"

cat > udp.xml <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>udp</transport_id>
        <type>UDPv4</type>
        <maxInitialPeersRange>32</maxInitialPeersRange>
        <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="udp">
      <rtps>
        <useBuiltinTransports>false</useBuiltinTransports>
        <userTransports><transport_id>udp</transport_id></userTransports>
        <builtin>
          <metatrafficUnicastLocatorList>
            <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
          </metatrafficUnicastLocatorList>
          <initialPeersList>
            <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
          </initialPeersList>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
XML
profile=udp.xml:udp
dds="dds: {domain: $domain, profile: xml, xml_file: udp.xml, xml_profile: udp}"
{
  echo "$dds"
  echo 'discovery: {enabled: true, pattern: "rt/*/points"}'
  echo "queue_depth: 100"
  echo "outputs: {status_period_s: 0.2}"
  echo "watchdog: {enabled: false}"
  "$pki_tool" config pki host_a
} > litamin2d.yaml
{
  echo "$dds"
  echo "store: {path: store.db}"
  echo "publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.2}"
  echo "watchdog: {enabled: false}"
  "$pki_tool" config pki aggregator
} > aggregator.yaml
"$tools/litamin2d/litamin2d" --check-config --config litamin2d.yaml
"$tools/aggregator/litamin2-aggregator" --check-config --config aggregator.yaml

"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 ||
  { cat sim.log; exit 1; }

echo "== capture lo"
tcpdump -i lo -U -w lo.pcap > tcpdump.log 2>&1 &
tcpdump_pid=$!
pids+=("$tcpdump_pid")
for _ in $(seq 1 50); do grep -q "listening on lo" tcpdump.log && break; sleep 0.1; done

echo "== 1. the secured chain"
start_services "$tools" "$probes" $domain --profile $profile --pki pki --identity operator
rm -f probe.ready
"$probes/daemon_probe" --domain $domain --profile $profile --pki pki --identity operator \
  --expect $frames --timeout 180 --stream $marker --ready-file probe.ready > probe.log 2>&1 &
probe_pid=$!
timeout 180 "$tools/replay/litamin2-replay" --domain $domain --profile $profile --pki pki \
  --identity vehicle_a --rate 10 --start-delay 4 seq --stream $marker > replay.log 2>&1 ||
  { cat replay.log; fail "the vehicle's replay"; }
wait "$probe_pid" || { cat probe.log; fail "the operator did not get every odometry message"; }
grep -E "^stream|^status $marker" probe.log
keyframes=$(status_value daemon_status.txt $marker keyframes)
if [ -z "$keyframes" ] || [ "$keyframes" -lt 1 ]; then fail "no keyframes"; fi
wait_status aggregator_status.txt $marker keyframes "$keyframes"
stored=$(sqlite3 -readonly store.db "select count(*) from keyframes")
[ "$stored" -eq "$keyframes" ] || fail "store: $stored keyframes, expected $keyframes"
echo "operator: $frames odometry messages; store: $stored keyframes"
timeout 60 "$tools/map_tiles/litamin2-map-tiles" --domain $domain --profile $profile --pki pki \
  --identity map_client --count 1 --timeout 20 --json > tiles.json 2> tiles.log ||
  { cat tiles.log; fail "the map client did not get a map tile"; }
echo "map client: $(grep -c '"ix"' tiles.json) map tile(s) over rt/litamin2/map_tiles"
received=$(status_value daemon_status.txt $marker frames_received)
streams_before=$(awk '$2 == "frames_received"' daemon_status.txt | wc -l)

echo "== 2. participants without a valid certificate change nothing"
for who in none rogue; do
  args=()
  [ "$who" = rogue ] && args=(--pki rogue --identity vehicle_a)
  status=0
  "$probes/daemon_probe" --domain $domain --profile $profile "${args[@]}" --expect 1 --timeout 8 \
    --stream $marker > "probe_$who.log" 2>&1 || status=$?
  grep -q "stream $marker: 0 odometry message(s)" "probe_$who.log" ||
    { cat "probe_$who.log"; fail "$who: odometry reached a participant without a valid certificate"; }
  status=0
  timeout 60 "$tools/replay/litamin2-replay" --domain $domain --profile $profile "${args[@]}" \
    --max --timeout 6 seq --stream fleet_intruder_$who > "replay_$who.log" 2>&1 ||
    status=$?
  [ "$status" -ne 0 ] || fail "$who: a replay found subscribers"
  status=0
  "$probes/raw_cdr_writer" --domain $domain --profile $profile "${args[@]}" --type patch \
    --stream fleet_intruder_$who --malformation valid --timeout 6 > "patch_$who.log" 2>&1 ||
    status=$?
  [ "$status" -ne 0 ] || fail "$who: map patches matched the aggregator"
  echo "$who: no odometry, replay and patches unmatched"
done
sleep 1
now=$(sqlite3 -readonly store.db "select count(*) from keyframes")
[ "$now" -eq "$stored" ] || fail "store rows changed: $stored -> $now"
[ "$(status_value daemon_status.txt $marker frames_received)" = "$received" ] ||
  fail "the daemon's counters changed"
[ "$(awk '$2 == "frames_received"' daemon_status.txt | wc -l)" -eq "$streams_before" ] ||
  fail "the daemon started a stream for an intruder"
grep -q intruder daemon.log aggregator.log && fail "an intruder's topic reached a process"
echo "daemon: still 1 stream, $received frames; store: still $now keyframes"

echo "== 3. valid participants without permission are refused"
refused() {  # refused LOG COMMAND...: the command fails and says it cannot create its endpoint
  local log=$1 status=0
  shift
  timeout 60 "$@" > "$log" 2>&1 || status=$?
  [ "$status" -ne 0 ] || { cat "$log"; fail "allowed: $*"; }
  grep -qiE "cannot (create|read)|refused|no subscribers" "$log" || { cat "$log"; fail "unclear: $log"; }
}
refused refuse_points.log "$tools/replay/litamin2-replay" --domain $domain --profile $profile \
  --pki pki --identity vehicle_b --max --timeout 6 seq --stream fleet_b_only
refused refuse_patches_vehicle.log "$probes/raw_cdr_writer" --domain $domain --profile $profile \
  --pki pki --identity vehicle_a --type patch --stream fleet_x --malformation valid --timeout 6
refused refuse_patches_operator.log "$probes/raw_cdr_writer" --domain $domain --profile $profile \
  --pki pki --identity operator --type patch --stream fleet_x --malformation valid --timeout 6
refused refuse_read_patches.log "$probes/status_probe" --domain $domain --profile $profile \
  --pki pki --identity vehicle_a --topic rt/litamin2/map_patches --timeout 2
refused refuse_read_tiles.log "$tools/map_tiles/litamin2-map-tiles" --domain $domain \
  --profile $profile --pki pki --identity vehicle_a --timeout 2
sed -n 's/^/  /p' refuse_points.log | grep -iE "cannot|refused" | head -2
[ "$(sqlite3 -readonly store.db "select count(*) from keyframes")" -eq "$stored" ] ||
  fail "store rows changed"

echo "== SIGTERM"
stop_services "$daemon_pid" "$aggregator_pid"
kill -INT "$tcpdump_pid"
wait "$tcpdump_pid" || true

echo "== 4. the wire holds no plaintext of the marker"
bytes=$(stat -c %s lo.pcap)
packets=$(tcpdump -r lo.pcap 2> /dev/null | wc -l)
[ "$packets" -gt 100 ] || fail "only $packets packets captured"
grep -c RTPS lo.pcap > /dev/null || fail "no RTPS in the capture"
hits=$(grep -a -c "$marker" lo.pcap || true)
echo "capture: $packets packets, $bytes bytes; plaintext '$marker': $hits"
[ "$hits" -eq 0 ] || fail "the marker crossed lo in plaintext"
grep -a -q "fleet_" lo.pcap && echo "(the grants' pattern fleet_* is visible: permissions travel signed, not encrypted)"
# Control: the same marker without security crosses lo in plaintext, so the check can fail.
tcpdump -i lo -U -w control.pcap > tcpdump_control.log 2>&1 &
tcpdump_pid=$!
pids+=("$tcpdump_pid")
for _ in $(seq 1 50); do grep -q "listening on lo" tcpdump_control.log && break; sleep 0.1; done
"$probes/daemon_probe" --domain $((domain + 1)) --profile $profile --expect 1 --timeout 20 \
  --stream $marker > probe_control.log 2>&1 &
control_pid=$!
"$probes/raw_cdr_writer" --domain $((domain + 1)) --profile $profile --type odom --stream $marker \
  --malformation valid --count 1 > writer_control.log 2>&1 || { cat writer_control.log; fail "control writer"; }
wait "$control_pid" || true
kill -INT "$tcpdump_pid"
wait "$tcpdump_pid" || true
control=$(grep -a -c "$marker" control.pcap || true)
echo "control without security: plaintext '$marker' in $control capture record(s)"
[ "$control" -gt 0 ] || fail "the control capture does not show the marker: the check proves nothing"

echo "== 5. bad files stop each process at start, naming them"
cp -r pki bad
# Tampered: one topic of the signed content changed.
sed -i 's#rt/fleet_\*/points#rt/*/points#' bad/host_a/permissions.p7s
sed -i 's#rt/litamin2/map_patches#rt/*#' bad/aggregator/permissions.p7s
# Expired permissions.
LITAMIN2_PKI_NOT_BEFORE=2020-01-01T00:00:00 LITAMIN2_PKI_NOT_AFTER=2021-01-01T00:00:00 \
  "$pki_tool" operator bad expired_op > /dev/null
check_start() {  # check_start TOOL CONFIG EXPECTED...
  local tool=$1 config=$2 status=0
  shift 2
  "$tool" --config "$config" > start.log 2>&1 || status=$?
  [ "$status" -eq 2 ] || { cat start.log; fail "$config: exit $status, expected 2"; }
  for e in "$@"; do grep -qF -- "$e" start.log || { cat start.log; fail "$config: no '$e'"; }; done
  echo "  $(basename "$tool") $config: $(tail -n 1 start.log | cut -c1-160)"
}
with() {  # with BASE FROM TO: BASE's config with a path replaced
  sed "s#$2#$3#" "$1"
}
with litamin2d.yaml pki/host_a/permissions.p7s bad/host_a/permissions.p7s > d_tampered.yaml
check_start "$tools/litamin2d/litamin2d" d_tampered.yaml security.permissions \
  bad/host_a/permissions.p7s "signature does not verify"
with aggregator.yaml pki/aggregator/permissions.p7s bad/aggregator/permissions.p7s > a_tampered.yaml
check_start "$tools/aggregator/litamin2-aggregator" a_tampered.yaml security.permissions \
  "signature does not verify"
with litamin2d.yaml pki/host_a/permissions.p7s pki/host_a/permissions.xml > d_unsigned.yaml
check_start "$tools/litamin2d/litamin2d" d_unsigned.yaml "not an S/MIME signed document"
with litamin2d.yaml pki/governance.p7s rogue/governance.p7s > d_other_ca.yaml
check_start "$tools/litamin2d/litamin2d" d_other_ca.yaml security.governance \
  "signature does not verify"
with aggregator.yaml pki/aggregator/permissions.p7s pki/host_a/permissions.p7s > a_mismatch.yaml
check_start "$tools/aggregator/litamin2-aggregator" a_mismatch.yaml security.permissions \
  "has no grant for the certificate's subject"
with aggregator.yaml pki/aggregator/key.pem pki/host_a/key.pem > a_key.yaml
check_start "$tools/aggregator/litamin2-aggregator" a_key.yaml security.private_key \
  "does not match security.certificate"
with litamin2d.yaml pki/host_a/cert.pem rogue/vehicle_a/cert.pem > d_cert.yaml
check_start "$tools/litamin2d/litamin2d" d_cert.yaml security.certificate \
  "is not issued by security.identity_ca"
sed "s#/pki/host_a/#/bad/expired_op/#g" litamin2d.yaml > d_expired.yaml
check_start "$tools/litamin2d/litamin2d" d_expired.yaml security.permissions \
  "expired on 2021-01-01T00:00:00"
with litamin2d.yaml pki/host_a/permissions.p7s pki/host_a/missing.p7s > d_missing.yaml
check_start "$tools/litamin2d/litamin2d" d_missing.yaml "security.permissions: cannot open"
echo PASS
