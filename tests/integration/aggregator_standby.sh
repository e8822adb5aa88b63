#!/usr/bin/env bash
# Hot standby of litamin2-aggregator through DDS ownership: two aggregators (A strength 2,
# B strength 1, each with its own store) read the same map patches (one publisher, reliable,
# transient-local: the daemons' durable history), and aggregator_probe reads the corrected
# keyframe poses EXCLUSIVELY, logging each sample's writer. Mid-ingest A is killed with
# SIGKILL: the probe must go on receiving poses, from B only, until both streams are complete.
#  - failover_s: kill -9 of A to the probe's first sample from B's writer; bounded by the
#    participant lease (LEASE_S, default 2 s) + 1 s (the poses period and the next patch).
#  - litamin2-map-tiles --exclusive gets B's tiles; without it (SHARED) it matches none.
#  - A restarted on its store after B is stopped completes from the publisher's history.
#  - The two maps: rebuilt from their keyframes (`export --replay`) they are byte-identical
#    (same keyframes in both stores); the stored live graphs (plain `export`) may differ in
#    the optimisation's timing (which patches formed a batch, when the background full pass
#    ran): the largest keyframe position difference is printed and bounded (MAX_LIVE_DIFF_M).
# In a private network namespace (unshare -n, only lo up) with a loopback-only UDP profile
# (127.0.0.1, unicast discovery, no multicast, no shared memory: kill -9 leaves no segment).
# Usage: aggregator_standby.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/traffic_counters.sh"
build=$1
work=$2
aggregator=$build/tools/aggregator/litamin2-aggregator
probe=$build/tests/integration/aggregator_probe
tiles_client=$build/tools/map_tiles/litamin2-map-tiles
sim=${LITAMIN2_SIM:-$build/tools/sim/litamin2-sim}
frames=${FRAMES:-120}
lease_s=${LEASE_S:-2}
max_live_diff_m=${MAX_LIVE_DIFF_M:-0.5}
domain=43
rm -rf "$work"
mkdir -p "$work"
cd "$work"

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  for f in a.log b.log probe.log publish.log; do [ -f "$f" ] && { echo "--- $f"; tail -20 "$f"; }; done
  exit 1
}

write_udp_lo_profile loopback_lease.xml "$lease_s"
profile=$PWD/loopback_lease.xml:litamin2

echo "== simulate $frames scans of the loop"
"$sim" --builtin loop --frames 0:$frames --output seq > sim.log 2>&1 || { cat sim.log; exit 1; }

config() {  # config FILE STORE STRENGTH
  cat > "$1" <<YAML
dds: {domain: $domain, profile: xml, xml_file: $PWD/loopback_lease.xml, xml_profile: litamin2}
store: {path: $PWD/$2}
publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.5}
standby: {strength: $3}
log_level: info
YAML
}
config a.yaml a.db 2
config b.yaml b.db 1

start_aggregator() {  # start_aggregator NAME: sets pid_NAME, waits until its DDS is up
  "$aggregator" --config "$1.yaml" >> "$1.log" 2>&1 &
  eval "pid_$1=$!"
  pids+=("$!")
  for _ in $(seq 1 200); do grep -q "DDS participant up" "$1.log" && return 0; sleep 0.05; done
  fail "aggregator $1 did not start"
}

stop_aggregator() {  # SIGTERM, must exit 0
  local pid=$1 status=0
  kill -TERM "$pid"
  wait "$pid" || status=$?
  [ "$status" -eq 0 ] || fail "aggregator $pid exited with $status after SIGTERM"
}

echo "== A (strength 2) and B (strength 1) on the same patches; probe exclusive"
start_aggregator a
start_aggregator b
grep -q "strength 2" a.log || fail "A does not report its strength"
# The probe's --expect is known once the publisher tracked the sequence (count file).
"$probe" --domain $domain --profile "$profile" publish --sequence seq --stream car_a \
  --stream car_b --rate 6 --linger 120 --count-file keyframes.txt > publish.log 2>&1 &
publisher=$!
pids+=("$publisher")
for _ in $(seq 1 600); do [ -s keyframes.txt ] && break; sleep 0.1; done
k=$(cat keyframes.txt)
[ "$k" -ge 20 ] || fail "only $k keyframes: too few for the test"
"$probe" --domain $domain --profile "$profile" poses --exclusive --log samples.txt \
  --stream car_a --stream car_b --expect "$k" --timeout 120 > probe.log 2>&1 &
probe_pid=$!
pids+=("$probe_pid")

# Kill A once a third of car_a's keyframes have corrected poses (mid-ingest).
third=$((k / 3))
for _ in $(seq 1 600); do
  awk -v n=$third '$2 == "car_a" && $3 >= n { found = 1 } END { exit !found }' samples.txt \
    2>/dev/null && break
  sleep 0.05
done
kill_ns=$(date +%s%N)
kill -9 "$pid_a"
wait "$pid_a" 2>/dev/null || true
echo "A killed with SIGKILL at $(awk -v n=$third 'END { print $3 }' samples.txt) keyframes"
status=0
wait "$probe_pid" || status=$?
cat probe.log
[ "$status" -eq 0 ] || fail "the probe did not get $k keyframes of both streams after the kill"

echo "== failover"
# Writers: the one before the kill (must be A's: the strongest) and the one after.
read -r before_writer before_count < <(awk -v t=$kill_ns '$1 < t { w = $4; n++ } END { print w, n }' samples.txt)
read -r first_b_ns after_writer < <(awk -v t=$kill_ns -v w="$before_writer" \
  '$1 >= t && $4 != w { print $1, $4; exit }' samples.txt)
[ -n "$before_writer" ] && [ "$before_count" -gt 0 ] || fail "no sample before the kill"
[ -n "${first_b_ns:-}" ] || fail "no sample from another writer after the kill"
# Nothing from the killed writer later than the lease after the kill (in-flight ones aside).
late_a=$(awk -v t=$((kill_ns + 200000000)) -v w="$before_writer" '$1 >= t && $4 == w' samples.txt | wc -l)
[ "$late_a" -eq 0 ] || fail "$late_a sample(s) from the killed writer after the kill"
# Exclusive: before the kill B's samples were discarded, apart from instances A had not
# written yet (ownership is per stream instance).
b_before=$(awk -v t=$kill_ns -v w="$after_writer" '$1 < t && $4 == w' samples.txt | wc -l)
writers=$(awk '{ print $4 }' samples.txt | sort -u | wc -l)
[ "$writers" -eq 2 ] || fail "$writers writers seen, expected 2"
failover_s=$(echo "($first_b_ns - $kill_ns) / 1000000000" | bc -l)
bound_s=$(echo "$lease_s + 1.0" | bc -l)
printf 'failover_s %.3f (kill -9 of A to the first poses from B; lease %s s, bound %s s)\n' \
  "$failover_s" "$lease_s" "$bound_s"
echo "samples: $before_count before the kill ($b_before of them from B), $(wc -l < samples.txt) in all"
[ "$(echo "$failover_s <= $bound_s" | bc -l)" -eq 1 ] || fail "failover $failover_s s > $bound_s s"

echo "== map tiles from B alone: an exclusive reader gets them, a shared one matches nothing"
"$tiles_client" --domain $domain --profile "$profile" --exclusive --count 1 --timeout 10 \
  --json > tiles_exclusive.json 2> tiles_exclusive.log || fail "no tile for the exclusive reader"
status=0
"$tiles_client" --domain $domain --profile "$profile" --count 1 --timeout 3 \
  > tiles_shared.json 2> tiles_shared.log || status=$?
[ "$status" -ne 0 ] || fail "a SHARED tile reader got tiles from an EXCLUSIVE writer"
echo "exclusive tile reader: tiles received; shared reader: none (as documented)"

echo "== B stopped; A restarted on its store completes from the publisher's history"
stop_aggregator "$pid_b"
start_aggregator a
"$probe" --domain $domain --profile "$profile" poses --exclusive --stream car_a --stream car_b \
  --expect "$k" --timeout 120 > probe_a.log 2>&1 || fail "restarted A did not complete"
stop_aggregator "$pid_a"
kill -9 "$publisher" 2>/dev/null || true

echo "== the two maps"
for s in a b; do
  "$aggregator" export --replay --store $s.db --map $s.ply --trajectories replay_$s \
    2> export_replay_$s.log || { cat export_replay_$s.log; exit 1; }
  "$aggregator" export --store $s.db --trajectories live_$s 2> export_live_$s.log ||
    { cat export_live_$s.log; exit 1; }
  grep -q "$((2 * k)) keyframe(s) of 2 stream(s)" export_live_$s.log ||
    fail "store $s lacks keyframes: $(cat export_live_$s.log)"
done
cmp a.ply b.ply || fail "the replayed maps differ"
diff -r replay_a replay_b > /dev/null || fail "the replayed trajectories differ"
echo "replayed from the keyframes: identical ($(stat -c %s a.ply)-byte map, $((2 * k)) keyframes)"
# The live graphs: the largest position difference of a keyframe between A's and B's.
live_diff=0
for f in live_a/*_kitti.txt; do
  d=$(paste "$f" "live_b/$(basename "$f")" | awk '{
        dx = $4 - $16; dy = $8 - $20; dz = $12 - $24; d = sqrt(dx*dx + dy*dy + dz*dz)
        if (d > m) m = d } END { printf "%.6f", m + 0 }')
  live_diff=$(echo "if ($d > $live_diff) $d else $live_diff" | bc -l)
done
identical_live=no
diff -r live_a live_b > /dev/null && identical_live=yes
printf 'live graphs: byte-identical %s, largest keyframe position difference %.6f m (bound %s)\n' \
  "$identical_live" "$live_diff" "$max_live_diff_m"
[ "$(echo "$live_diff <= $max_live_diff_m" | bc -l)" -eq 1 ] || fail "live maps differ by $live_diff m"
# Passed: the simulated scans go (kept on failure for a look; CI has a disk of its own size).
rm -rf seq
printf '{"failover_s": %.3f, "lease_s": %s, "keyframes": %d, "live_max_diff_m": %.6f}\n' \
  "$failover_s" "$lease_s" "$((2 * k))" "$live_diff"
