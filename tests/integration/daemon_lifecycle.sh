#!/usr/bin/env bash
# litamin2d's command line, config errors, sd_notify protocol and signal handling, in a private
# network namespace. Usage: daemon_lifecycle.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
here=$(cd "$(dirname "$0")" && pwd)
build=$1
work=$2
source_dir=$3
daemon=$build/tools/litamin2d/litamin2d
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

echo "== command line"
"$daemon" --help | grep -q -- "--check-config" || fail "--help"
"$daemon" --version | grep -q "^litamin2d " || fail "--version"
"$daemon" --check-config --config "$source_dir/config/litamin2d.yaml" | grep -q ": ok" ||
  fail "shipped config does not check"
printf 'discovery: {enabled: true}\nqueue_depth: 0\n' > bad.yaml
status=0
"$daemon" --check-config --config bad.yaml 2> bad.err || status=$?
[ "$status" -eq 2 ] || fail "bad config: exit $status, expected 2"
grep -q "bad.yaml: queue_depth: 0 is out of range" bad.err || fail "message: $(cat bad.err)"
status=0
"$daemon" --config /nonexistent.yaml 2> missing.err || status=$?
[ "$status" -eq 2 ] || fail "missing config: exit $status"

cat > daemon.yaml <<YAML
dds: {domain: 23, profile: loopback}
discovery: {enabled: true, pattern: "rt/*/points"}
threads: 1
outputs: {status_period_s: 0.2}
log_level: debug
YAML

# Runs the daemon with a fake NOTIFY_SOCKET and WatchdogSec=0.4 s, stops it with signal $1 after
# $2 seconds, and checks the notifications and the exit. With $3 = journal, stderr is "the
# journal's" ($JOURNAL_STREAM set) and lines carry the syslog priority prefix; else they do not.
run_with_signal() {
  local signal=$1 seconds=$2 journal=${3:-} socket="$work/notify_$1.sock"
  rm -f "$socket" "notify_$1.log"
  python3 "$here/daemon_notify_listener.py" "$socket" "notify_$1.log" 30 &
  local listener=$!
  for _ in $(seq 1 100); do [ -S "$socket" ] && break; sleep 0.05; done
  local journal_stream=
  [ "$journal" = journal ] && journal_stream=8:4242
  JOURNAL_STREAM=$journal_stream NOTIFY_SOCKET=$socket WATCHDOG_USEC=400000 "$daemon" \
    --config daemon.yaml > "daemon_$1.log" 2>&1 &
  local pid=$!
  # Counted from READY=1: the start (the heap touched first, memory.prefault_mb) comes before it.
  for _ in $(seq 1 200); do grep -q " READY=1$" "notify_$1.log" 2>/dev/null && break; sleep 0.05; done
  sleep "$seconds"
  kill -0 $pid || { cat "daemon_$1.log"; fail "daemon died early"; }
  local t0 t1 status=0
  t0=$(date +%s%N)
  kill -"$signal" $pid
  for _ in $(seq 1 50); do kill -0 $pid 2>/dev/null || break; sleep 0.05; done
  kill -0 $pid 2>/dev/null && { kill -9 $pid; cat "daemon_$1.log"; fail "still running 2.5 s after SIG$signal"; }
  wait $pid || status=$?
  t1=$(date +%s%N)
  wait $listener || true
  echo "SIG$signal: exit $status after $(( (t1 - t0) / 1000000 )) ms"
  cat "notify_$1.log"
  [ "$status" -eq 0 ] || { cat "daemon_$1.log"; fail "exit status $status"; }
  [ $(( (t1 - t0) / 1000000 )) -lt 2000 ] || fail "took too long"
  grep -q " READY=1$" "notify_$1.log" || fail "no READY=1"
  grep -q " STOPPING=1$" "notify_$1.log" || fail "no STOPPING=1"
  grep -q " STATUS=" "notify_$1.log" || fail "no STATUS="
  local pings
  pings=$(grep -c " WATCHDOG=1$" "notify_$1.log" || true)
  # One ping at start, then one every 0.2 s.
  [ "$pings" -ge $(( ${seconds%.*} * 4 )) ] || fail "only $pings WATCHDOG=1 in ${seconds} s"
  # READY comes before the first WATCHDOG, STOPPING last.
  [ "$(grep -m1 -E 'READY|WATCHDOG' "notify_$1.log" | cut -d' ' -f2)" = "READY=1" ] ||
    fail "WATCHDOG before READY"
  [ "$(tail -n 1 "notify_$1.log" | cut -d' ' -f2)" = "STOPPING=1" ] || fail "STOPPING not last"
  # The heap touched before DDS starts (memory.prefault_mb auto: 64 MiB and 32 for the one
  # stream a discovering daemon counts), before READY=1.
  # AddressSanitizer's allocator refuses mallopt: the daemon then says so and touches nothing.
  grep -q "heap policy left as it is: " "daemon_$1.log" ||
    grep -q "heap: 96 MiB touched at start in [0-9.]* s (memory.prefault_mb)" "daemon_$1.log" ||
    fail "no heap prefault in the log"
  if [ "$journal" = journal ]; then
    grep -q "^<6>info: " "daemon_$1.log" || fail "journal log lines lack the syslog priority prefix"
  else
    grep -q "^info: " "daemon_$1.log" || fail "no plain info lines"
    grep -q "^<[0-9]>" "daemon_$1.log" && fail "syslog priority prefix without the journal"
  fi
  return 0
}

echo "== sd_notify and SIGTERM (stderr to the journal)"
run_with_signal TERM 2 journal
echo "== sd_notify and SIGINT (stderr to a file)"
run_with_signal INT 1

echo "== SIGHUP: the log level changes at once, other changes are reported, a bad file is refused"
socket=$work/notify_hup.sock
sed 's/^log_level: .*/log_level: info/' daemon.yaml > hup.yaml
rm -f "$socket" notify_hup.log
python3 "$here/daemon_notify_listener.py" "$socket" notify_hup.log 30 &
listener=$!
for _ in $(seq 1 100); do [ -S "$socket" ] && break; sleep 0.05; done
NOTIFY_SOCKET=$socket "$daemon" --config hup.yaml > daemon_hup.log 2>&1 &
pid=$!
for _ in $(seq 1 100); do grep -q "READY=1" notify_hup.log.tmp 2>/dev/null && break; sleep 0.05; done
sed -i 's/^log_level: .*/log_level: debug/; s/^threads: .*/threads: 2/' hup.yaml
kill -HUP $pid
for _ in $(seq 1 40); do grep -q "reload: log level" daemon_hup.log && break; sleep 0.05; done
kill -0 $pid || { cat daemon_hup.log; fail "SIGHUP ended the daemon"; }
grep -q "reload: log level info -> debug" daemon_hup.log || { cat daemon_hup.log; fail "log level not reloaded"; }
grep -q "reload: 'threads' changed in hup.yaml: it needs a restart" daemon_hup.log ||
  fail "changed threads not reported"
printf 'queue_depth: 0\n' >> hup.yaml
kill -HUP $pid
for _ in $(seq 1 40); do grep -q "reload: invalid configuration" daemon_hup.log && break; sleep 0.05; done
grep -q "reload: invalid configuration, nothing changed: hup.yaml: queue_depth" daemon_hup.log ||
  { cat daemon_hup.log; fail "invalid reload not refused"; }
kill -0 $pid || fail "an invalid reload ended the daemon"
kill -TERM $pid
status=0
wait $pid || status=$?
wait $listener || true
[ "$status" -eq 0 ] || { cat daemon_hup.log; fail "exit status $status after SIGHUP and SIGTERM"; }
[ "$(grep -c ' RELOADING=1' notify_hup.log)" -eq 2 ] || { cat notify_hup.log; fail "RELOADING=1 not sent twice"; }
# Each RELOADING=1 is followed by READY=1 (three READY in all, with the start's).
[ "$(grep -c ' READY=1$' notify_hup.log)" -eq 3 ] || { cat notify_hup.log; fail "READY=1 not sent after each reload"; }
echo PASS
