#!/usr/bin/env bash
# Map-patch stream ids bound to the publishing identity (issue 14, docs/security.md "Stream
# binding"), in a private network namespace (only lo up), on the loopback profile.
#  A. Secured (scripts/litamin2-pki; daemon host_1 granted car_1_*, host_2 granted car_2_*):
#     - the chain works: a vehicle's stream car_1_a goes through litamin2d (its patches in
#       partition car_1_a) into the store, nothing rejected;
#     - host_1's identity cannot create a map patch writer in partition car_2_x, nor in "*"
#       (Fast DDS's access control refuses the writer);
#     - participants with valid identities writing patches whose stream id is not their
#       partition (host_1: partition car_1_a, stream car_2_x; host_2: partition car_2_x, stream
#       car_1_a) match the aggregator, which rejects each patch: store rows unchanged,
#       patches_rejected.stream_not_bound counts them.
#  B. Unsecured: the same mismatch is rejected and counted; a control patch whose stream is
#     its writer's partition is stored (so the rejection is the check, not the writer).
# Usage: stream_binding.sh BUILD_DIR WORK_DIR SOURCE_DIR
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
count=3
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

"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 ||
  { cat sim.log; exit 1; }

# configs DOMAIN SECURED(0|1): litamin2d.yaml and aggregator.yaml in the current folder.
configs() {
  local domain=$1 secured=$2
  rm -f store.db
  {
    echo "dds: {domain: $domain, profile: loopback}"
    echo 'discovery: {enabled: true, pattern: "rt/*/points"}'
    echo "queue_depth: 100"
    echo "outputs: {status_period_s: 0.2}"
    echo "watchdog: {enabled: false}"
    if [ "$secured" = 1 ]; then "$pki_tool" config ../pki host_1; fi
  } > litamin2d.yaml
  {
    echo "dds: {domain: $domain, profile: loopback}"
    echo "store: {path: store.db}"
    echo "publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.2}"
    echo "watchdog: {enabled: false}"
    if [ "$secured" = 1 ]; then "$pki_tool" config ../pki aggregator; fi
  } > aggregator.yaml
  return 0
}

# chain DOMAIN ARGS...: starts both services and replays the vehicle's stream car_1_a; the store
# then holds its keyframes ($stored), nothing is rejected.
chain() {
  local domain=$1
  shift
  start_services "$tools" "$probes" "$domain" "$@"
  timeout 180 "$tools/replay/litamin2-replay" --domain "$domain" "${vehicle[@]}" --rate 10 \
    --start-delay 3 ../seq --stream car_1_a > replay.log 2>&1 ||
    { cat replay.log; fail "the vehicle's replay"; }
  for _ in $(seq 1 100); do [ -n "$(status_value daemon_status.txt car_1_a keyframes)" ] && break; sleep 0.1; done
  keyframes=$(status_value daemon_status.txt car_1_a keyframes)
  if [ -z "$keyframes" ] || [ "$keyframes" -lt 1 ]; then fail "no keyframes"; fi
  wait_status aggregator_status.txt car_1_a keyframes "$keyframes"
  stored=$(sqlite3 -readonly store.db "select count(*) from keyframes")
  [ "$stored" -eq "$keyframes" ] || fail "store: $stored keyframes, expected $keyframes"
  [ "$(status_value aggregator_status.txt litamin2-aggregator patches_rejected)" = 0 ] ||
    fail "patches rejected in the legitimate chain"
  echo "chain: car_1_a's $keyframes keyframes stored through partition car_1_a, none rejected"
}

# mismatch DOMAIN EXPECTED_TOTAL ARGS...: a raw writer (ARGS: identity, --stream, --partition)
# matches the aggregator; waits until stream_not_bound reaches EXPECTED_TOTAL.
mismatch() {
  local domain=$1 expected=$2
  shift 2
  "$probes/raw_cdr_writer" --domain "$domain" --type patch --malformation valid --count $count \
    --timeout 15 "$@" > mismatch.log 2>&1 || { cat mismatch.log; fail "raw writer: $*"; }
  wait_status aggregator_status.txt litamin2-aggregator patches_rejected.stream_not_bound "$expected"
  echo "  $* -> rejected, stream_not_bound = $expected"
}

echo "== A. secured"
"$pki_tool" init pki > /dev/null
"$pki_tool" vehicle pki vehicle_1 --streams 'car_1_*' > /dev/null
"$pki_tool" daemon pki host_1 --streams 'car_1_*' > /dev/null
"$pki_tool" daemon pki host_2 --streams 'car_2_*' > /dev/null
"$pki_tool" aggregator pki aggregator > /dev/null
"$pki_tool" operator pki operator > /dev/null
mkdir secured && cd secured
domain=61
configs $domain 1
vehicle=(--profile loopback --pki ../pki --identity vehicle_1)
chain $domain --profile loopback --pki ../pki --identity operator
for partition in car_2_x '*'; do
  status=0
  "$probes/raw_cdr_writer" --domain $domain --profile loopback --pki ../pki --identity host_1 \
    --type patch --stream car_2_x --partition "$partition" --malformation valid --timeout 6 \
    > refused.log 2>&1 || status=$?
  [ "$status" -ne 0 ] || { cat refused.log; fail "host_1 wrote patches in partition $partition"; }
  grep -q "cannot create a writer of rt/litamin2/map_patches in partition $partition" refused.log ||
    { cat refused.log; fail "unclear refusal"; }
  grep -qF "$partition partition not found in rule" refused.log ||
    { cat refused.log; fail "not refused by the access control"; }
  echo "  host_1 in partition '$partition': refused ($(grep -m1 -o "$partition partition not found in rule" refused.log))"
done
mismatch $domain $count --profile loopback --pki ../pki --identity host_1 --stream car_2_x \
  --partition car_1_a
mismatch $domain $((2 * count)) --profile loopback --pki ../pki --identity host_2 --stream car_1_a \
  --partition car_2_x
grep -q "dropped a bad map patch (stream_not_bound)" aggregator.log || fail "no rejection logged"
now=$(sqlite3 -readonly store.db "select count(*) from keyframes")
[ "$now" -eq "$stored" ] || fail "store rows changed: $stored -> $now"
[ "$(sqlite3 -readonly store.db "select count(*) from keyframes where stream = 'car_2_x'")" -eq 0 ] ||
  fail "car_2_x reached the store"
echo "store: still $now keyframes"
stop_services "$daemon_pid" "$aggregator_pid"
cd ..

echo "== B. unsecured"
mkdir unsecured && cd unsecured
domain=62
configs $domain 0
vehicle=(--profile loopback)
chain $domain --profile loopback
mismatch $domain $count --profile loopback --stream car_2_x --partition car_1_a
# Control: the same raw writer with its stream as its partition is stored.
"$probes/raw_cdr_writer" --domain $domain --profile loopback --type patch --malformation valid \
  --count $count --timeout 15 --stream car_1_raw > control.log 2>&1 ||
  { cat control.log; fail "control writer"; }
wait_status aggregator_status.txt car_1_raw keyframes 1
now=$(sqlite3 -readonly store.db "select count(*) from keyframes")
[ "$now" -eq $((stored + 1)) ] || fail "store: $now keyframes, expected $stored + 1 (control)"
[ "$(status_value aggregator_status.txt litamin2-aggregator patches_rejected.stream_not_bound)" = $count ] ||
  fail "the control was rejected"
echo "control: car_1_raw in partition car_1_raw stored; store $stored -> $now keyframes"
stop_services "$daemon_pid" "$aggregator_pid"
echo PASS
