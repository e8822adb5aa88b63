#!/usr/bin/env bash
# rt/tf and rt/tf_static of litamin2d read by Cyclone DDS, in a private network namespace:
# simulated scans -> cyclone_client -> litamin2d (Fast DDS) -> cyclone_tf_reader. The stream has
# an extrinsic and a sensor_frame of its own; every odom -> base_link transform must equal the
# odometry of the same stamp bit for bit, and a reader that joins after the daemon published
# rt/tf_static (transient-local) must get base_link -> the sensor frame with the extrinsic.
# litamin2-aggregator runs too: its map -> <stream>/odom transforms (with each map-frame pose)
# must reach the reader, at odometry stamps, and a late reader of its map cloud
# (sensor_msgs/PointCloud2, transient-local) gets the map's points in frame map.
# Usage: cyclone_tf.sh LITAMIN2D AGGREGATOR SIM CYCLONE_CLIENT CYCLONE_TF_READER CYCLONE_XML
#        WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
daemon=$1
aggregator=$2
sim=$3
client=$4
reader=$5
cyclone_xml=$6
work=$7
frames=20
domain=44
stream=tfcar
rm -rf "$work"
mkdir -p "$work"
cd "$work"

if ip -o link show | awk -F': ' '{print $2}' | grep -qv '^lo$'; then
  echo "not in a private network namespace:"; ip -o link show; exit 1
fi
export CYCLONEDDS_URI="file://$cyclone_xml"

echo "== simulate"
"$sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 || { cat sim.log; exit 1; }

# Sensor 1.2 m ahead and 1.5 m up, turned 90 degrees about z: q = (0, 0, sin 45, cos 45).
cat > litamin2d.yaml <<YAML
dds: {domain: $domain, profile: loopback}
streams:
  - id: $stream
    extrinsic: {xyz: [1.2, 0, 1.5], rpy_deg: [0, 0, 90]}
    sensor_frame: velodyne
discovery: {enabled: false}
threads: 2
queue_depth: 100
log_level: info
YAML

cat > aggregator.yaml <<YAML
dds: {domain: $domain, profile: loopback}
topics: {map_cloud: rt/litamin2/map_cloud}
publish: {tiles_period_s: 0.2}
store: {path: aggregator.db}
watchdog: {enabled: false}
YAML

pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
}
trap cleanup EXIT

echo "== start litamin2d (domain $domain)"
"$daemon" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
pids+=($daemon_pid)

echo "== start litamin2-aggregator"
"$aggregator" --config aggregator.yaml > aggregator.log 2>&1 &
aggregator_pid=$!
pids+=($aggregator_pid)

echo "== cyclone_tf_reader on rt/tf and rt/$stream/odom"
timeout 300 "$reader" --stream $stream --domain $domain --count $frames --map-count 1 \
  --timeout 240 \
  --output tf.txt > reader.log 2>&1 &
reader_pid=$!
pids+=($reader_pid)
for _ in $(seq 1 600); do grep -q '^matched' reader.log && break; sleep 0.05; done
grep -q '^matched' reader.log || { echo "tf reader not matched"; cat reader.log daemon.log; exit 1; }

# At 10 Hz, as a sensor: the aggregator reads a stream's odometry from when the stream's first
# map patch has reached it, so the later frames' odometry reaches it too.
echo "== cyclone_client: $frames scans in at 10 Hz"
timeout 300 "$client" seq --domain $domain --stream $stream --output received.txt --period 0.1 \
  --frame-timeout 10 --match-timeout 30 > client.log 2>&1 || { cat client.log daemon.log; exit 1; }
reader_status=0
wait $reader_pid || reader_status=$?
cat reader.log
[ "$reader_status" -eq 0 ] || { echo "tf reader failed with $reader_status"; cat daemon.log; exit 1; }
grep -q "^$frames transform(s) of stream $stream read, $frames equal to their odometry" reader.log ||
  { echo "not every transform matched its odometry"; exit 1; }
test "$(grep -c "^tf [0-9]* $stream/odom $stream/base_link " tf.txt)" -eq $frames ||
  { echo "expected $frames transforms $stream/odom -> $stream/base_link:"; cat tf.txt; exit 1; }

maps=$(grep -c "^tf [0-9]* map $stream/odom " tf.txt || true)
echo "$maps map -> $stream/odom transform(s) from the aggregator"
[ "$maps" -ge 1 ] || { echo "no map transform"; cat aggregator.log; exit 1; }

echo "== a late reader of rt/tf_static"
timeout 60 "$reader" --static --stream $stream --domain $domain --timeout 30 \
  --output tf_static.txt > static.log 2>&1 || { cat static.log daemon.log; exit 1; }
cat static.log tf_static.txt
test "$(wc -l < tf_static.txt)" -eq 1 || { echo "expected one static transform"; exit 1; }
awk -v s="$stream" '
  $1 == "tf" && $3 == s "/base_link" && $4 == "velodyne" {
    e[1] = 1.2; e[2] = 0; e[3] = 1.5; e[4] = 0; e[5] = 0; e[6] = sqrt(0.5); e[7] = sqrt(0.5)
    for (i = 1; i <= 7; ++i) { d = $(i + 4) - e[i]; if (d < 0) d = -d; if (d > 1e-12) exit 1 }
    ok = 1
  }
  END { exit ok ? 0 : 1 }' tf_static.txt ||
  { echo "rt/tf_static does not hold $stream/base_link -> velodyne with the extrinsic"; exit 1; }

echo "== a late reader of the aggregator's map cloud"
timeout 60 "$reader" --cloud rt/litamin2/map_cloud --stream $stream --domain $domain \
  --timeout 30 --output cloud.txt > cloud.log 2>&1 || { cat cloud.log aggregator.log; exit 1; }
cat cloud.txt
grep -q '^cloud map [0-9]* 16 x:0:7 y:4:7 z:8:7 count:12:6$' cloud.txt ||
  { echo "unexpected map cloud layout"; exit 1; }
points=$(awk '$1 == "cloud" {print $3}' cloud.txt)
valid=$(awk '$1 == "valid" {print $2}' cloud.txt)
[ "$points" -gt 100 ] && [ "$valid" -eq "$points" ] ||
  { echo "map cloud: $points points, $valid valid"; exit 1; }

kill -TERM $daemon_pid $aggregator_pid
daemon_status=0
wait $daemon_pid || daemon_status=$?
aggregator_status=0
wait $aggregator_pid || aggregator_status=$?
[ "$daemon_status" -eq 0 ] || { echo "litamin2d exited with $daemon_status"; cat daemon.log; exit 1; }
[ "$aggregator_status" -eq 0 ] ||
  { echo "litamin2-aggregator exited with $aggregator_status"; cat aggregator.log; exit 1; }
echo PASS
