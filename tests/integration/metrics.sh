#!/usr/bin/env bash
# The Prometheus endpoint and rt/diagnostics of litamin2d and litamin2-aggregator, in a private
# network namespace: both started with metrics.listen on loopback; /readyz and /healthz answer
# 200; /metrics parses as Prometheus text (prometheus_check.py: every sample has a # TYPE,
# counters end in _total, histogram buckets monotone with +Inf = _count, build_info); after
# simulated scans are replayed (cyclone_client) the frame counters and the latency histogram
# have counted every frame and the aggregator counts keyframes; a Cyclone DDS reader of
# rt/diagnostics gets both processes' statuses; a second daemon on the same port fails to start
# with a clear error and exit 1.
# Usage: metrics.sh LITAMIN2D AGGREGATOR SIM CYCLONE_CLIENT DIAGNOSTICS_READER CYCLONE_XML
#        PROMETHEUS_CHECK WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
daemon=$1
aggregator=$2
sim=$3
client=$4
diagnostics_reader=$5
cyclone_xml=$6
check=$7
work=$8
frames=20
domain=46
stream=mcar
daemon_port=19464
aggregator_port=19465
rm -rf "$work"
mkdir -p "$work"
cd "$work"

if ip -o link show | awk -F': ' '{print $2}' | grep -qv '^lo$'; then
  echo "not in a private network namespace:"; ip -o link show; exit 1
fi
export CYCLONEDDS_URI="file://$cyclone_xml"

http_code() { curl -s -o /dev/null -w '%{http_code}' --max-time 5 "$1" || true; }
scrape() { curl -sf --max-time 5 "http://127.0.0.1:$1/metrics" > "$2"; }
value() { awk -v k="$2" '$1 == k {print $2}' "$1"; }

echo "== simulate"
"$sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 || { cat sim.log; exit 1; }

cat > litamin2d.yaml <<YAML
dds: {domain: $domain, profile: loopback}
streams:
  - id: $stream
discovery: {enabled: false}
threads: 2
queue_depth: 100
metrics: {listen: "127.0.0.1:$daemon_port"}
YAML

cat > aggregator.yaml <<YAML
dds: {domain: $domain, profile: loopback}
store: {path: aggregator.db}
watchdog: {enabled: false}
metrics: {listen: "127.0.0.1:$aggregator_port"}
YAML

pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
}
trap cleanup EXIT

echo "== start litamin2d and litamin2-aggregator"
"$daemon" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
pids+=($daemon_pid)
"$aggregator" --config aggregator.yaml > aggregator.log 2>&1 &
aggregator_pid=$!
pids+=($aggregator_pid)

for port in $daemon_port $aggregator_port; do
  code=000
  for _ in $(seq 1 300); do
    code=$(http_code "http://127.0.0.1:$port/readyz")
    [ "$code" = 200 ] && break
    sleep 0.1
  done
  [ "$code" = 200 ] || { echo "/readyz on $port: $code"; cat daemon.log aggregator.log; exit 1; }
  code=$(http_code "http://127.0.0.1:$port/healthz")
  [ "$code" = 200 ] || { echo "/healthz on $port: $code"; exit 1; }
  code=$(http_code "http://127.0.0.1:$port/nothing")
  [ "$code" = 404 ] || { echo "/nothing on $port: $code (expected 404)"; exit 1; }
  echo "port $port: /readyz 200, /healthz 200"
done

processed="litamin2_stream_frames_processed_total{stream=\"$stream\"}"
received="litamin2_stream_frames_received_total{stream=\"$stream\"}"
latency_count="litamin2_stream_latency_seconds_count{stream=\"$stream\"}"
latency_inf="litamin2_stream_latency_seconds_bucket{stream=\"$stream\",le=\"+Inf\"}"
keyframes="litamin2_aggregator_keyframes_total"
scrape $daemon_port daemon_before.txt
python3 "$check" daemon_before.txt "$processed" > check_before.txt || { cat check_before.txt; exit 1; }
cat check_before.txt
before=$(value check_before.txt "$processed")
[ "$before" = 0 ] || { echo "frames processed before the replay: $before"; exit 1; }

echo "== Cyclone DDS readers of rt/diagnostics"
timeout 200 "$diagnostics_reader" --domain $domain --expect "litamin2d: $stream" \
  --key frames_processed --min $frames --timeout 150 > diag_daemon.log 2>&1 &
diag_daemon_pid=$!
pids+=($diag_daemon_pid)
timeout 200 "$diagnostics_reader" --domain $domain --expect litamin2-aggregator \
  --key keyframes --min 1 --timeout 150 > diag_aggregator.log 2>&1 &
diag_aggregator_pid=$!
pids+=($diag_aggregator_pid)

echo "== cyclone_client: $frames scans"
timeout 300 "$client" seq --domain $domain --stream $stream --output received.txt --period 0.05 \
  --frame-timeout 10 --match-timeout 30 > client.log 2>&1 || { cat client.log daemon.log; exit 1; }

# The endpoint serves what the main loop rendered at most 1 s ago; the aggregator's keyframes
# arrive after the daemon's patches.
ok=0
for _ in $(seq 1 100); do
  scrape $daemon_port daemon_after.txt
  scrape $aggregator_port aggregator_after.txt
  python3 "$check" daemon_after.txt "$processed" "$received" "$latency_count" "$latency_inf" \
    > check_daemon.txt || { cat check_daemon.txt; exit 1; }
  python3 "$check" aggregator_after.txt "$keyframes" > check_aggregator.txt ||
    { cat check_aggregator.txt; exit 1; }
  after=$(value check_daemon.txt "$processed")
  kf=$(value check_aggregator.txt "$keyframes")
  if [ "$after" = "$frames" ] && [ "$kf" != absent ] && [ "${kf%.*}" -ge 1 ]; then ok=1; break; fi
  sleep 0.3
done
cat check_daemon.txt check_aggregator.txt
[ "$ok" = 1 ] || { echo "frames processed $after (want $frames), keyframes $kf"; exit 1; }
[ "$(value check_daemon.txt "$received")" = "$frames" ] || { echo "frames received"; exit 1; }
[ "$(value check_daemon.txt "$latency_count")" = "$frames" ] ||
  { echo "latency histogram did not count every frame"; exit 1; }
for family in litamin2_stream_frames_dropped_total litamin2_stream_bad_messages_total \
              litamin2_stream_queue_depth litamin2_stream_latency_seconds; do
  grep -q "^# TYPE $family " daemon_after.txt || { echo "no $family"; exit 1; }
done
for family in litamin2_aggregator_loops_total litamin2_aggregator_merges_total \
              litamin2_aggregator_optimization_seconds litamin2_aggregator_store_size_bytes \
              litamin2_aggregator_patches_rejected_total litamin2_aggregator_queue_depth; do
  grep -q "^# TYPE $family " aggregator_after.txt || { echo "no $family"; exit 1; }
done
store_bytes=$(awk '$1 == "litamin2_aggregator_store_size_bytes" {print $2}' aggregator_after.txt)
[ "$store_bytes" -gt 0 ] || { echo "store size $store_bytes"; exit 1; }
echo "store size $store_bytes bytes"

for p in $diag_daemon_pid $diag_aggregator_pid; do
  s=0
  wait $p || s=$?
  cat diag_daemon.log diag_aggregator.log
  [ "$s" -eq 0 ] || { echo "rt/diagnostics reader failed with $s"; exit 1; }
done
grep -q "^status litamin2d: $stream level [0-9] frames_processed=$frames " diag_daemon.log ||
  { echo "no daemon status with every frame on rt/diagnostics"; exit 1; }

echo "== a second litamin2d on the same metrics port"
sed "s/domain: $domain/domain: $((domain + 1))/" litamin2d.yaml > second.yaml
status=0
timeout 30 "$daemon" --config second.yaml > second.log 2>&1 || status=$?
cat second.log
[ "$status" -eq 1 ] || { echo "expected exit 1, got $status"; exit 1; }
grep -q "cannot listen on 127.0.0.1:$daemon_port" second.log ||
  { echo "no clear bind error"; exit 1; }
grep -q "DDS participant up" second.log && { echo "DDS started despite the bind failure"; exit 1; }

kill -TERM $daemon_pid $aggregator_pid
daemon_status=0
wait $daemon_pid || daemon_status=$?
aggregator_status=0
wait $aggregator_pid || aggregator_status=$?
[ "$daemon_status" -eq 0 ] || { echo "litamin2d exited with $daemon_status"; cat daemon.log; exit 1; }
[ "$aggregator_status" -eq 0 ] ||
  { echo "litamin2-aggregator exited with $aggregator_status"; cat aggregator.log; exit 1; }
echo PASS
