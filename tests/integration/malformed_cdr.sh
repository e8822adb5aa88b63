#!/usr/bin/env bash
# Malformed CDR over real DDS to both processes (issue 14): raw_cdr_writer sends PointCloud2
# samples with a bad bool, a truncated sequence and a sequence length beyond the payload to
# litamin2d, and map patches and odometry with a truncated sequence and a length beyond the
# payload to litamin2-aggregator. Both keep running, count every sample in their status, store
# nothing of it, and keep serving a good stream replayed meanwhile. In a private network
# namespace, loopback profile. Usage: malformed_cdr.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/service_helpers.sh"
build=$1
work=$2
tools=$build/tools
probes=$build/tests/integration
frames=12
count=3
domain=47
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*"; for f in daemon.log aggregator.log; do echo "--- $f"; tail -n 30 "$f"; done; exit 1; }

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

"$tools/sim/litamin2-sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 ||
  { cat sim.log; exit 1; }

cat > litamin2d.yaml <<YAML
dds: {domain: $domain, profile: loopback}
streams: [{id: good}, {id: raw_stream}]
queue_depth: 100
outputs: {status_period_s: 0.2}
watchdog: {enabled: false}
YAML
cat > aggregator.yaml <<YAML
dds: {domain: $domain, profile: loopback}
store: {path: store.db}
publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.2}
watchdog: {enabled: false}
YAML

start_services "$tools" "$probes" $domain

alive() { kill -0 "$1" 2>/dev/null || fail "$2 died"; }

echo "== malformed PointCloud2 samples to litamin2d (rt/raw_stream/points)"
for m in bad_bool truncated length_beyond; do
  "$probes/raw_cdr_writer" --domain $domain --type points --stream raw_stream --malformation $m \
    --count $count || fail "raw writer ($m)"
done
wait_status daemon_status.txt raw_stream bad_messages $((3 * count))
wait_status daemon_status.txt raw_stream bad_messages.malformed_cdr $((3 * count))
alive "$daemon_pid" litamin2d

echo "== malformed map patches to litamin2-aggregator (rt/litamin2/map_patches)"
for m in truncated length_beyond; do
  "$probes/raw_cdr_writer" --domain $domain --type patch --stream raw_stream --malformation $m \
    --count $count || fail "raw writer (patch $m)"
done
wait_status aggregator_status.txt litamin2-aggregator patches_rejected.malformed_cdr $((2 * count))
alive "$aggregator_pid" litamin2-aggregator

echo "== a good stream meanwhile: every frame processed, its keyframes stored"
rm -f probe.ready
"$probes/daemon_probe" --domain $domain --expect $frames --timeout 120 --stream good \
  --ready-file probe.ready > probe.log 2>&1 &
probe_pid=$!
for _ in $(seq 1 200); do [ -f probe.ready ] && break; sleep 0.1; done
timeout 120 "$tools/replay/litamin2-replay" --domain $domain --profile loopback --rate 20 \
  seq --stream good > replay.log 2>&1 || { cat replay.log; fail "replay"; }
wait "$probe_pid" || { cat probe.log; fail "the good stream was not served"; }
grep -E "^stream|^status good" probe.log

echo "== malformed odometry to litamin2-aggregator (rt/good/odom, read once good has keyframes)"
keyframes=$(status_value daemon_status.txt good keyframes)
if [ -z "$keyframes" ] || [ "$keyframes" -lt 1 ]; then fail "no keyframe of good"; fi
wait_status aggregator_status.txt good keyframes "$keyframes"
before=$(status_value aggregator_status.txt good odometry_rejected)
for _ in $(seq 1 100); do grep -q "stream good: reading rt/good/odom" aggregator.log && break; sleep 0.1; done
"$probes/raw_cdr_writer" --domain $domain --type odom --stream good --malformation truncated \
  --count $count || fail "raw writer (odom)"
wait_status aggregator_status.txt good odometry_rejected $((before + count))
alive "$aggregator_pid" litamin2-aggregator
alive "$daemon_pid" litamin2d

echo "== nothing of the malformed stream reached the store"
stored_raw=$(sqlite3 -readonly store.db "select count(*) from keyframes where stream = 'raw_stream'")
stored_good=$(sqlite3 -readonly store.db "select count(*) from keyframes where stream = 'good'")
[ "$stored_raw" -eq 0 ] || fail "$stored_raw keyframes of raw_stream stored"
[ "$stored_good" -eq "$keyframes" ] || fail "$stored_good keyframes of good stored, expected $keyframes"
echo "store: $stored_good keyframe(s) of good, 0 of raw_stream"
grep -E "^(raw_stream|good) (bad_messages|frames_processed)|^litamin2-aggregator (patches_rejected|malformed_samples)|^good odometry_rejected" \
  daemon_status.txt aggregator_status.txt | sed 's/^/  /'

echo "== SIGTERM: both exit 0"
stop_services "$daemon_pid" "$aggregator_pid"
echo PASS
