#!/usr/bin/env bash
# DDS replay integration test: litamin2-replay -> dds_replay_subscriber over the loopback-only
# profile, inside a private network namespace (unshare -n, loopback up) when we may create one.
# usage: dds_replay.sh LITAMIN2_REPLAY DDS_REPLAY_SUBSCRIBER WORK_DIR
set -u
REPLAY=$1
SUB=$2
WORK=$3

if [ -z "${DDS_REPLAY_IN_NETNS:-}" ] && unshare -n true 2>/dev/null; then
  export DDS_REPLAY_IN_NETNS=1
  exec unshare -n bash -c 'ip link set lo up && exec bash "$0" "$@"' "$0" "$@"
fi
if [ -n "${DDS_REPLAY_IN_NETNS:-}" ]; then
  echo "running in a private network namespace"
else
  echo "unshare -n unavailable: running on the host, loopback-only profile"
fi

rm -rf "$WORK"
mkdir -p "$WORK"
# A domain of our own: shared-memory ports are not isolated by the network namespace.
DOMAIN=$((100 + $$ % 100))
FAIL=0
SUB_PID=""
cleanup() { [ -n "$SUB_PID" ] && kill "$SUB_PID" 2>/dev/null; }
trap cleanup EXIT

check() {  # check NAME EXPECTED_RC ACTUAL_RC
  if [ "$2" = "$3" ]; then
    echo "ok: $1"
  else
    echo "FAIL: $1 (exit $3, expected $2)"
    FAIL=1
  fi
}

"$SUB" make-sequence "$WORK/a" 5 20000 1 || exit 1
"$SUB" make-sequence "$WORK/b" 7 30002 2 || exit 1

start_subscriber() {  # start_subscriber NAME ID=DIR...
  local name=$1
  shift
  rm -f "$WORK/$name.ready"
  timeout 90 "$SUB" subscribe "$DOMAIN" 60 "$WORK/$name.ready" "$@" >"$WORK/$name.sub.log" 2>&1 &
  SUB_PID=$!
  for _ in $(seq 1 200); do
    [ -f "$WORK/$name.ready" ] && return 0
    sleep 0.1
  done
  echo "subscriber $name not ready"
  return 1
}

finish_subscriber() {  # finish_subscriber NAME -> sets SUB_RC
  wait "$SUB_PID"
  SUB_RC=$?
  SUB_PID=""
  cat "$WORK/$1.sub.log"
}

# 1. Two streams at once, reliable keep-all, as fast as possible: every scan arrives identical.
start_subscriber two car1="$WORK/a" fleet/car2="$WORK/b" || exit 1
timeout 90 "$REPLAY" --stream car1 --stream fleet/car2 --max --domain "$DOMAIN" \
  --wait-subscribers 1 --timeout 30 "$WORK/a" "$WORK/b" >"$WORK/two.replay.log" 2>&1
RC=$?
cat "$WORK/two.replay.log"
check "two streams: replay exit" 0 $RC
finish_subscriber two
check "two streams: all scans identical" 0 $SUB_RC
grep -q "^car1: 5/5 scans received, identical" "$WORK/two.sub.log" || { echo "FAIL: car1 line"; FAIL=1; }
grep -q "^fleet/car2: 7/7 scans received, identical" "$WORK/two.sub.log" || { echo "FAIL: car2 line"; FAIL=1; }

# 2. Paced: 5 frames at 20 Hz take at least 4 periods (0.2 s).
start_subscriber paced car1="$WORK/a" || exit 1
T0=$(date +%s.%N)
timeout 90 "$REPLAY" --stream car1 --rate 20 --domain "$DOMAIN" --profile loopback \
  --timeout 30 "$WORK/a" >"$WORK/paced.replay.log" 2>&1
RC=$?
T1=$(date +%s.%N)
cat "$WORK/paced.replay.log"
check "paced: replay exit" 0 $RC
finish_subscriber paced
check "paced: all scans identical" 0 $SUB_RC
awk -v a="$T0" -v b="$T1" 'BEGIN { exit !(b - a >= 0.2) }' || { echo "FAIL: 20 Hz too fast"; FAIL=1; }

# 2b. Preloaded and staggered: two streams at 20 Hz, the second half a period after the first;
#     every scan arrives identical, and the whole takes at least 6.5 periods (0.325 s).
start_subscriber staggered car1="$WORK/a" fleet/car2="$WORK/b" || exit 1
T0=$(date +%s.%N)
timeout 90 "$REPLAY" --stream car1 --stream fleet/car2 --rate 20 --stagger --preload \
  --domain "$DOMAIN" --profile loopback --timeout 30 "$WORK/a" "$WORK/b" \
  >"$WORK/staggered.replay.log" 2>&1
RC=$?
T1=$(date +%s.%N)
cat "$WORK/staggered.replay.log"
check "staggered: replay exit" 0 $RC
finish_subscriber staggered
check "staggered: all scans identical" 0 $SUB_RC
grep -q "preloaded 12 scans" "$WORK/staggered.replay.log" || { echo "FAIL: no preload"; FAIL=1; }
awk -v a="$T0" -v b="$T1" 'BEGIN { exit !(b - a >= 0.325) }' ||
  { echo "FAIL: staggered 20 Hz too fast"; FAIL=1; }

# 3. Large scans (120001 points, 1.9 MB) on two streams at --max with a shallow writer history
#    (--depth 2): the reliable writers must block or retry, never drop a scan.
"$SUB" make-sequence "$WORK/big1" 20 120001 3 || exit 1
"$SUB" make-sequence "$WORK/big2" 20 120001 4 || exit 1
start_subscriber big big1="$WORK/big1" big2="$WORK/big2" || exit 1
timeout 120 "$REPLAY" --stream big1 --stream big2 --max --depth 2 --domain "$DOMAIN" \
  --timeout 30 "$WORK/big1" "$WORK/big2" >"$WORK/big.replay.log" 2>&1
RC=$?
grep -v "RTPS_TRANSPORT_SHM" "$WORK/big.replay.log"
check "large scans: replay exit" 0 $RC
finish_subscriber big
check "large scans: all scans identical" 0 $SUB_RC
rm -rf "$WORK/big1" "$WORK/big2"

# 4. Nobody listening: bounded wait, exit 4 with a clear message.
timeout 30 "$REPLAY" --stream car1 --domain "$DOMAIN" --timeout 1 "$WORK/a" \
  >"$WORK/nosub.log" 2>&1
check "no subscribers: exit 4" 4 $?
grep -q "0 of 1 reader(s) matched" "$WORK/nosub.log" || { echo "FAIL: no-subscriber message"; cat "$WORK/nosub.log"; FAIL=1; }

# 5. Usage errors exit 2 with one "litamin2-replay: error:" line, input errors 1, before any DDS
#    traffic; --help exits 0.
"$REPLAY" --help >/dev/null 2>&1
check "--help" 0 $?
"$REPLAY" --stream car1 --stream car2 "$WORK/a" >/dev/null 2>&1
check "stream/folder count mismatch" 2 $?
"$REPLAY" --stream 1car "$WORK/a" >"$WORK/badid.log" 2>&1
check "invalid stream id" 2 $?
grep -q "^litamin2-replay: error: .*starts with a digit" "$WORK/badid.log" || { echo "FAIL: bad id message"; FAIL=1; }
"$REPLAY" --stream car1 "$WORK/missing" >/dev/null 2>&1
check "missing sequence" 1 $?
"$REPLAY" --stream car1 --profile udp "$WORK/a" >/dev/null 2>&1
check "unknown profile" 2 $?
"$REPLAY" --stream car1 --frames 9: "$WORK/a" >/dev/null 2>&1
check "frames beyond the sequence" 2 $?
"$REPLAY" --stream car1 --rate 0 "$WORK/a" >/dev/null 2>&1
check "rate 0" 2 $?
"$REPLAY" --stream car1 --max --stagger "$WORK/a" >/dev/null 2>&1
check "--stagger with --max" 2 $?

exit $FAIL
