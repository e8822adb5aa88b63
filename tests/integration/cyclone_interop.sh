#!/usr/bin/env bash
# Interop with an independent DDS implementation, in a private network namespace: simulated
# scans -> cyclone_client (Cyclone DDS C API) -> litamin2d (Fast DDS) -> cyclone_client. Every
# frame must get its odometry, bit-identical to litamin2-odometry's pose of the same scan.
# Usage: cyclone_interop.sh LITAMIN2D SIM ODOMETRY CYCLONE_CLIENT CYCLONE_XML WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
daemon=$1
sim=$2
odometry=$3
client=$4
cyclone_xml=$5
work=$6
frames=30
domain=43
stream=cyc
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# Nothing but loopback here (daemon_netns.sh): DDS traffic cannot leave the machine.
if ip -o link show | awk -F': ' '{print $2}' | grep -qv '^lo$'; then
  echo "not in a private network namespace:"; ip -o link show; exit 1
fi

echo "== simulate and run the offline odometry"
"$sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 || { cat sim.log; exit 1; }
"$odometry" seq --output offline --quiet > odometry.log 2>&1 || { cat odometry.log; exit 1; }
test "$(wc -l < offline/poses_kitti.txt)" -eq $frames

cat > litamin2d.yaml <<YAML
dds: {domain: $domain, profile: loopback}
streams:
  - id: $stream
discovery: {enabled: false}
threads: 2
queue_depth: 100
outputs: {status_period_s: 0.5}
log_level: info
YAML

daemon_pid=
cleanup() {
  if [ -n "$daemon_pid" ] && kill -0 "$daemon_pid" 2>/dev/null; then kill -9 "$daemon_pid"; fi
}
trap cleanup EXIT

echo "== start litamin2d (Fast DDS, loopback profile, domain $domain)"
"$daemon" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!

echo "== cyclone_client: $frames scans in, odometry out"
client_status=0
CYCLONEDDS_URI="file://$cyclone_xml" timeout 300 "$client" seq --domain $domain \
  --stream $stream --output received.txt --frame-timeout 10 --match-timeout 30 \
  --reference offline/poses_kitti.txt --reference-out expected.txt > client.log 2>&1 ||
  client_status=$?
cat client.log
if [ "$client_status" -ne 0 ]; then
  echo "cyclone_client failed with $client_status"; cat daemon.log; exit 1
fi
test "$(wc -l < received.txt)" -eq $frames ||
  { echo "received $(wc -l < received.txt) of $frames poses"; exit 1; }
test "$(wc -l < expected.txt)" -eq $frames
grep -q "$frames of $frames poses bit-identical" client.log || { echo "poses differ"; exit 1; }
cmp received.txt expected.txt || { echo "received poses differ from the offline ones"; exit 1; }
grep -q "stream $stream: reading rt/$stream/points (reliable)" daemon.log ||
  { echo "litamin2d did not read the Cyclone writer reliably"; cat daemon.log; exit 1; }

echo "== SIGTERM"
t0=$(date +%s%N)
kill -TERM $daemon_pid
for _ in $(seq 1 50); do kill -0 $daemon_pid 2>/dev/null || break; sleep 0.05; done
if kill -0 $daemon_pid 2>/dev/null; then
  echo "litamin2d still running 2.5 s after SIGTERM"; cat daemon.log; exit 1
fi
daemon_status=0
wait $daemon_pid || daemon_status=$?
t1=$(date +%s%N)
daemon_pid=
echo "litamin2d exited with $daemon_status, $(( (t1 - t0) / 1000000 )) ms after SIGTERM"
tail -n 5 daemon.log
[ "$daemon_status" -eq 0 ] || exit 1
echo PASS
