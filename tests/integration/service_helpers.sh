# Sourced by the integration scripts that run litamin2d and litamin2-aggregator with a
# status_probe recording their status (tests/integration/status_probe).

# status_value FILE ID KEY: the latest value of KEY in the status entry ID (empty if none yet).
status_value() {
  awk -v id="$2" -v key="$3" '$1 == id && $2 == key { print $3 }' "$1" 2>/dev/null || true
}

# wait_status FILE ID KEY EXPECTED: waits (up to 30 s) until the status says so; fails otherwise.
wait_status() {
  for _ in $(seq 1 300); do [ "$(status_value "$@")" = "$4" ] && return 0; sleep 0.1; done
  fail "$1: $2 $3 is '$(status_value "$1" "$2" "$3")', expected $4"
}

# stop_services PID...: SIGTERM to each; each must exit 0.
stop_services() {
  local pid status
  for pid in "$@"; do
    kill -TERM "$pid"
    status=0
    wait "$pid" || status=$?
    [ "$status" -eq 0 ] || fail "pid $pid exited with $status after SIGTERM"
  done
}

# start_services TOOLS_DIR PROBES_DIR DOMAIN [PROBE_ARGS...]: litamin2-aggregator
# (aggregator.yaml, log aggregator.log) and litamin2d (litamin2d.yaml, daemon.log) in the
# current folder, and a status_probe of each (PROBE_ARGS: --profile, --pki, ...) recording
# daemon_status.txt and aggregator_status.txt. Sets aggregator_pid and daemon_pid; appends
# every pid to the array pids.
start_services() {
  local tools=$1 probes=$2 domain=$3
  shift 3
  "$tools/aggregator/litamin2-aggregator" --config aggregator.yaml > aggregator.log 2>&1 &
  aggregator_pid=$!
  "$tools/litamin2d/litamin2d" --config litamin2d.yaml > daemon.log 2>&1 &
  daemon_pid=$!
  pids+=("$aggregator_pid" "$daemon_pid")
  "$probes/status_probe" --domain "$domain" "$@" --topic rt/litamin2/status \
    --out daemon_status.txt > status_d.log 2>&1 &
  pids+=($!)
  "$probes/status_probe" --domain "$domain" "$@" --topic rt/litamin2/aggregator/status \
    --out aggregator_status.txt > status_a.log 2>&1 &
  pids+=($!)
}
