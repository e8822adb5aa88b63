#!/usr/bin/env bash
# The command-line convention of every tool (common/cli.hpp), run for real on each executable
# given: a usage error (unknown option; --frames / --config with a bad or missing value where the
# tool has them) exits 2 with exactly one "prog: error: " line on stderr naming what is wrong and
# nothing on stdout;
# --version and -V exit 0 with "prog <version>"; --help exits 0 and names --version.
# Usage: check_cli.sh TOOL_PATH...
set -uo pipefail
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
failures=0 checks=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

usage_error() {  # usage_error PROG WHAT NAMED ARGS...: exit 2, one prefixed line naming NAMED
  local prog=$1 what=$2 named=$3 path=$4; shift 4
  checks=$((checks + 1))
  "$path" "$@" >"$work/out" 2>"$work/err"; local rc=$?
  local lines; lines=$(wc -l <"$work/err")
  if [ "$rc" -ne 2 ]; then fail "$prog $what: exit $rc, expected 2: $(cat "$work/err")"; return; fi
  if [ "$lines" -ne 1 ]; then fail "$prog $what: $lines stderr lines: $(cat "$work/err")"; return; fi
  if ! grep -q -- "^$prog: error: .*$named" "$work/err"; then
    fail "$prog $what: not '$prog: error: ...$named': $(cat "$work/err")"; return
  fi
  if [ -s "$work/out" ]; then fail "$prog $what: wrote to stdout: $(cat "$work/out")"; return; fi
  echo "ok   $prog $what: $(cat "$work/err")"
}

for path in "$@"; do
  prog=$(basename "$path")
  usage_error "$prog" "unknown option" --no-such-option-xyz "$path" --no-such-option-xyz
  for v in --version -V; do
    checks=$((checks + 1))
    out=$("$path" "$v" 2>"$work/err"); rc=$?
    if [ "$rc" -ne 0 ] || ! grep -Eq "^$prog [0-9]+\.[0-9]+" <<<"$out"; then
      fail "$prog $v: exit $rc, stdout '$out', stderr $(cat "$work/err")"
    else
      echo "ok   $prog $v: $out"
    fi
  done
  checks=$((checks + 1))
  "$path" --help >"$work/help" 2>&1; rc=$?
  if [ "$rc" -ne 0 ] || ! grep -q -- "--version" "$work/help"; then
    fail "$prog --help: exit $rc or no --version in it"
  else
    echo "ok   $prog --help"
  fi
  if grep -q -- "--frames" "$work/help"; then
    usage_error "$prog" "--frames 5:2" "--frames 5:2 is empty" "$path" --frames 5:2
    usage_error "$prog" "--frames x" "--frames must look like A:B" "$path" --frames x
    usage_error "$prog" "--frames (no value)" "--frames" "$path" --frames
  fi
  if grep -q -- "--config" "$work/help"; then
    usage_error "$prog" "--config (no value)" "--config" "$path" --config
  fi
done
echo "$((checks - failures)) of $checks checks passed"
[ "$failures" -eq 0 ]
