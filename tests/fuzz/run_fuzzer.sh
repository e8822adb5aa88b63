#!/usr/bin/env bash
# Runs one libFuzzer harness for a while from a scratch copy of its seed corpus (the repo's
# corpus is never written). Usage: run_fuzzer.sh FUZZER CORPUS SECONDS WORK_DIR
# Prints the executions reached; exits non-zero (with the crash report and the input's path
# under WORK_DIR/artifacts) when the harness found a crash, a leak, a timeout (10 s) or an
# allocation beyond 2 GiB.
set -euo pipefail
fuzzer=$1 corpus=$2 seconds=$3 work=$4
rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts"
cp -r "$corpus"/. "$work/corpus/"
status=0
"$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=3072 -malloc_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" > "$work/fuzz.log" 2>&1 ||
  status=$?
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/fuzz.log")
units=$(find "$work/corpus" -type f | wc -l)
echo "$(basename "$fuzzer"): ${execs:-?} executions in ${seconds} s, corpus $units inputs"
if [ "$status" -ne 0 ]; then
  tail -n 60 "$work/fuzz.log"
  ls -l "$work/artifacts"
  exit 1
fi
