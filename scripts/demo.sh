#!/usr/bin/env bash
# The main job on its built-in default: installs what is missing, builds (Release), simulates a
# small fleet (2 vehicles on the same streets of the simulator's built-in loop, HDL-64 scans),
# replays it over DDS into litamin2d (loopback-only transport: no traffic leaves this machine),
# checks every odometry message against the offline tool, prints per-stream accuracy and
# throughput, and shuts everything down with SIGTERM. Output in ${OUT:-out/demo}.
# Env: FRAMES (default 150 per vehicle), DOMAIN (DDS domain, default 42), RATE (Hz, default 10).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
build="${BUILD_DIR:-$root/build}"
bin="$build/tools"
probe="$build/tests/integration/daemon_probe"
out=${OUT:-$root/out/demo}
frames=${FRAMES:-150}
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

cat > litamin2d.yaml <<YAML
# Demo config: the shipped default (discover every rt/*/points, loopback-only transport) on
# domain $domain.
dds: {domain: $domain, profile: loopback}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 2
queue_depth: 100
outputs: {status_period_s: 1.0}
YAML

daemon_pid=""
probe_pid=""
cleanup() {
  for pid in $probe_pid $daemon_pid; do kill -9 "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT

echo "== starting litamin2d (domain $domain, loopback profile) and an odometry subscriber"
"$bin/litamin2d/litamin2d" --config litamin2d.yaml > daemon.log 2>&1 &
daemon_pid=$!
probe_args=()
for s in "${streams[@]}"; do probe_args+=(--stream "$s=offline_$s/poses_kitti.txt"); done
rm -f probe.ready
"$probe" --domain "$domain" --profile loopback --expect "$frames" --timeout 600 \
  --ready-file probe.ready --poses-out received_ "${probe_args[@]}" > probe.log 2>&1 &
probe_pid=$!

echo "== replaying the fleet at $rate Hz into rt/<vehicle>/points"
replay_args=()
for s in "${streams[@]}"; do replay_args+=(--stream "$s"); done
start=$(date +%s.%N)
"$bin/replay/litamin2-replay" --domain "$domain" --profile loopback --rate "$rate" --timeout 60 \
  "${replay_args[@]}" $(for s in "${streams[@]}"; do echo "fleet/$s"; done) > replay.log 2>&1 \
  || { cat replay.log daemon.log; exit 1; }
probe_rc=0
wait "$probe_pid" || probe_rc=$?
probe_pid=""
end=$(date +%s.%N)

echo "== SIGTERM to litamin2d"
kill -TERM "$daemon_pid"
daemon_rc=0
wait "$daemon_pid" || daemon_rc=$?
daemon_pid=""

echo
echo "== results"
grep -E "^stream |^status " probe.log | sed 's/^/  /'
grep -E "shut down" daemon.log | sed 's/^<[0-9]>info: /  litamin2d /'
json_value() {  # json_value FILE KEY: the number after "KEY": (or n/a)
  local v
  v=$(grep -o "\"$2\": [^,}]*" "$1" | head -1 | awk '{print $2}')
  [ -n "$v" ] && [ "$v" != null ] && echo "$v" || echo n/a
}
for s in "${streams[@]}"; do
  f="offline_$s/stats.json"
  printf '  %s accuracy: KITTI %s %% / %s deg/100 m, ATE %s m (offline; the daemon poses are identical)\n' \
    "$s" "$(json_value "$f" kitti_translation_percent)" "$(json_value "$f" kitti_rotation_deg_per_100m)" \
    "$(json_value "$f" ate_translation_m)"
done
printf '  replay + processing: %.1f s for %d x %d frames at %s Hz\n' "$(echo "$end - $start" | bc)" \
  ${#streams[@]} "$frames" "$rate"
echo "  logs and poses: $out (daemon.log, probe.log, received_*, offline_*)"
[ "$probe_rc" -eq 0 ] && [ "$daemon_rc" -eq 0 ] || { echo "demo FAILED (probe $probe_rc, daemon $daemon_rc)"; exit 1; }
echo "demo OK"
