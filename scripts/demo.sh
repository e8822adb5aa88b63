#!/usr/bin/env bash
# The main job on its built-in default: installs what is missing, builds (Release), simulates a
# small fleet (2 vehicles on the same streets of the simulator's built-in loop, HDL-64 scans,
# the second one driving the other way), replays it over DDS into litamin2d (loopback-only
# transport: no traffic leaves this machine), checks every odometry message against the offline
# tool, feeds litamin2d's map patches to litamin2-aggregator (loop closure between the vehicles,
# pose graph, SQLite store), exports the global map (PLY) and trajectories, plots them (PNG) and
# prints per-stream drift and ATE before and after loop closure, and the error of the merged
# frame; everything is shut down with SIGTERM. Output in ${OUT:-out/demo}.
# Env: FRAMES (default 387 per vehicle: the whole built-in loop), DOMAIN (DDS domain, default 42), RATE (Hz, default 10),
# MERGE_BOUND (metres, default 1.0: largest allowed error of a merged vehicle's keyframes in the
# first vehicle's frame), MAP_ODOM_BOUND (metres, default 1.0: the same for every pose the
# aggregator published live on rt/<vehicle>/map_odom in the map frame), BUILD_DIR,
# DEMO_SKIP_BUILD, SECURE=1 (the whole chain with DDS-Security: a fleet PKI made by
# scripts/litamin2-pki in $OUT/pki, one identity per vehicle, the daemon, the aggregator and an
# operator for the demo's probes; the secured litamin2d.yaml and aggregator.yaml stay in $OUT).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${DEMO_SKIP_BUILD:-}" ]; then  # the fleet ctest runs it on an existing build
  "$root/scripts/install-deps.sh"
  "$root/scripts/build.sh"
fi
build="${BUILD_DIR:-$root/build}"
bin="$build/tools"
probe="$build/tests/integration/daemon_probe"
map_odom_probe="$build/tests/integration/map_odom_probe"
out=${OUT:-$root/out/demo}
frames=${FRAMES:-387}
domain=${DOMAIN:-42}
rate=${RATE:-10}
streams=(vehicle_00 vehicle_01)
mkdir -p "$out"
cd "$out"

echo "== simulating ${#streams[@]} vehicles x $frames frames on the built-in loop ($out/fleet)"
rm -rf fleet
"$bin/sim/litamin2-sim" --builtin loop --fleet ${#streams[@]} --frames 0:"$frames" --output fleet \
  2> sim.log || { cat sim.log; exit 1; }

echo "== offline reference: litamin2-odometry on each vehicle"
for s in "${streams[@]}"; do
  "$bin/odometry/litamin2-odometry" --output "offline_$s" "fleet/$s" | sed "s/^/  $s: /"
done

# With SECURE=1: the fleet's PKI, and a --pki/--identity pair for each participant.
security_section() { :; }
secure=()
operator=()
if [ "${SECURE:-0}" = 1 ]; then
  echo "== SECURE=1: a fleet PKI in $out/pki (scripts/litamin2-pki)"
  rm -rf pki
  "$root/scripts/litamin2-pki" init pki --domains "$domain-$domain" | sed 's/^/  /'
  for s in "${streams[@]}"; do
    "$root/scripts/litamin2-pki" vehicle pki "$s" --streams "$s" | sed 's/^/  /'
  done
  "$root/scripts/litamin2-pki" daemon pki litamin2d --streams "vehicle_*" | sed 's/^/  /'
  "$root/scripts/litamin2-pki" aggregator pki aggregator | sed 's/^/  /'
  "$root/scripts/litamin2-pki" operator pki operator | sed 's/^/  /'
  security_section() { "$root/scripts/litamin2-pki" config pki "$1"; }
  secure=(--pki pki)
  operator=(--pki pki --identity operator)
fi

cat > litamin2d.yaml <<YAML
# Demo config: the shipped default (discover every rt/*/points, loopback-only transport) on
# domain $domain.
dds: {domain: $domain, profile: loopback}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 2
queue_depth: 100
outputs: {status_period_s: 1.0}
$(security_section litamin2d)
YAML

cat > aggregator.yaml <<YAML
# Demo config: the shipped default on domain $domain, with the store in the demo's folder.
dds: {domain: $domain, profile: loopback}
store: {path: aggregator.db}
watchdog: {enabled: false}
$(security_section aggregator)
YAML

daemon_pid=""
probe_pid=""
aggregator_pid=""
map_odom_pid=""
cleanup() {
  for pid in $probe_pid $daemon_pid $aggregator_pid $map_odom_pid; do
    kill -9 "$pid" 2>/dev/null || true
  done
}
trap cleanup EXIT

echo "== starting litamin2-aggregator (store $out/aggregator.db)"
rm -f aggregator.db aggregator.db-wal aggregator.db-shm
"$bin/aggregator/litamin2-aggregator" --config aggregator.yaml > aggregator.log 2>&1 &
aggregator_pid=$!
echo "== recording the aggregator's map-frame odometry (rt/<vehicle>/map_odom)"
rm -f map_odom_*.txt
"$map_odom_probe" --domain "$domain" --profile loopback --out map_odom_ "${operator[@]}" \
  $(for s in "${streams[@]}"; do echo --stream "$s"; done) > map_odom_probe.log 2>&1 &
map_odom_pid=$!

echo "== starting litamin2d (domain $domain, loopback profile) and an odometry subscriber"
"$bin/litamin2d/litamin2d" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
probe_args=()
for s in "${streams[@]}"; do probe_args+=(--stream "$s=offline_$s/poses_kitti.txt"); done
rm -f probe.ready
"$probe" --domain "$domain" --profile loopback --expect "$frames" --timeout 600 "${operator[@]}" \
  --ready-file probe.ready --poses-out received_ "${probe_args[@]}" > probe.log 2>&1 &
probe_pid=$!

echo "== replaying the fleet at $rate Hz into rt/<vehicle>/points"
start=$(date +%s.%N)
if [ "${SECURE:-0}" = 1 ]; then
  # One replay per vehicle, each with its vehicle's identity (it may publish only its stream).
  replay_pids=()
  for s in "${streams[@]}"; do
    "$bin/replay/litamin2-replay" --domain "$domain" --profile loopback --rate "$rate" \
      --timeout 60 --start-delay 4 "${secure[@]}" --identity "$s" --stream "$s" "fleet/$s" \
      > "replay_$s.log" 2>&1 &
    replay_pids+=($!)
  done
  for p in "${replay_pids[@]}"; do wait "$p" || { cat replay_*.log daemon.log; exit 1; }; done
  cat replay_*.log > replay.log
else
  replay_args=()
  for s in "${streams[@]}"; do replay_args+=(--stream "$s"); done
  "$bin/replay/litamin2-replay" --domain "$domain" --profile loopback --rate "$rate" --timeout 60 \
    --start-delay 2 \
    "${replay_args[@]}" $(for s in "${streams[@]}"; do echo "fleet/$s"; done) > replay.log 2>&1 \
    || { cat replay.log daemon.log; exit 1; }
fi
probe_rc=0
wait "$probe_pid" || probe_rc=$?
probe_pid=""
end=$(date +%s.%N)

echo "== SIGTERM to litamin2d"
kill -TERM "$daemon_pid"
daemon_rc=0
wait "$daemon_pid" || daemon_rc=$?
daemon_pid=""

expected=0
for s in "${streams[@]}"; do
  expected=$((expected + $(grep -o '"keyframes": [0-9]*' "offline_$s/stats.json" | awk '{print $2}')))
done
echo "== waiting for the aggregator to store all $expected keyframes, then SIGTERM"
stored=0
for _ in $(seq 1 120); do
  stored=$(sqlite3 -readonly aggregator.db "select count(*) from keyframes" 2>/dev/null || echo 0)
  [ "$stored" -ge "$expected" ] && break
  sleep 0.5
done
kill -TERM "$aggregator_pid"
aggregator_rc=0
wait "$aggregator_pid" || aggregator_rc=$?
aggregator_pid=""
kill -TERM "$map_odom_pid"
wait "$map_odom_pid" || true
map_odom_pid=""

echo "== export: global map and trajectories"
rm -rf trajectories report
"$bin/aggregator/litamin2-aggregator" export --store aggregator.db --map map.ply \
  --trajectories trajectories > export.log 2>&1 || { cat export.log; exit 1; }
sed 's/^/  /' export.log

echo
echo "== results"
grep -E "^stream |^status " probe.log | sed 's/^/  /'
grep -E "shut down" daemon.log | sed 's/^<[0-9]>info: /  litamin2d /'
json_value() {  # json_value FILE KEY: the number after "KEY": to 4 decimals (or n/a)
  local v
  v=$(grep -o "\"$2\": [^,}]*" "$1" | head -1 | awk '{print $2}')
  [ -n "$v" ] && [ "$v" != null ] && LC_ALL=C printf '%.4f' "$v" || echo n/a
}
for s in "${streams[@]}"; do
  f="offline_$s/stats.json"
  printf '  %s accuracy: KITTI %s %% / %s deg/100 m, ATE %s m (offline; the daemon poses are identical)\n' \
    "$s" "$(json_value "$f" kitti_translation_percent)" "$(json_value "$f" kitti_rotation_deg_per_100m)" \
    "$(json_value "$f" ate_translation_m)"
done
printf '  replay + processing: %.1f s for %d x %d frames at %s Hz\n' "$(echo "$end - $start" | bc)" \
  ${#streams[@]} "$frames" "$rate"
echo "  aggregator: $stored of $expected keyframes stored; export: $(head -1 export.log | sed 's/^[^:]*: //')"
echo
echo "== per-stream drift and ATE before (litamin2d odometry) and after loop closure (aggregator)"
report_rc=0
python3 "$root/scripts/lib/fleet_report.py" "$bin/eval/litamin2-eval" fleet received_ trajectories \
  report "${MERGE_BOUND:-1.0}" || report_rc=$?
echo
echo "== each vehicle's current pose in the map frame, as published live (rt/<vehicle>/map_odom)"
map_odom_rc=0
python3 "$root/scripts/lib/map_odom_report.py" fleet map_odom_ "${MAP_ODOM_BOUND:-1.0}" \
  || map_odom_rc=$?
for s in "${streams[@]}"; do
  "$bin/eval/litamin2-eval" --gt "report/${s}_gt_map_keyframes.txt" \
    --est "report/${s}_slam_keyframes.txt" --plot "trajectory_$s.png" > /dev/null
done
echo "  map: $out/map.ply; trajectory plots: $out/trajectory_*.png; trajectories: $out/trajectories"
echo "  logs and poses: $out (daemon.log, aggregator.log, probe.log, received_*, offline_*, report/)"
[ "$probe_rc" -eq 0 ] && [ "$daemon_rc" -eq 0 ] && [ "$aggregator_rc" -eq 0 ] && [ "$stored" -ge "$expected" ] \
  && [ "$report_rc" -eq 0 ] && [ "$map_odom_rc" -eq 0 ] ||
  { echo "demo FAILED (probe $probe_rc, daemon $daemon_rc, aggregator $aggregator_rc, stored $stored of $expected, report $report_rc, map_odom $map_odom_rc)"; exit 1; }
[ "${SECURE:-0}" = 1 ] &&
  echo "  SECURE=1: PKI in $out/pki, secured configs $out/litamin2d.yaml and $out/aggregator.yaml"
echo "demo OK"
