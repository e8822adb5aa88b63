#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (Release), runs every test under ctest
# (the fuzz harnesses among them, replaying their corpora: fuzz_replay_*), then the harnesses
# under libFuzzer with ASan/UBSan for FUZZ_SECONDS (default 20) each (scripts/fuzz.sh: clang, a
# build of its own in build-fuzz, ~7 min on 2 cores; LITAMIN2_RUN_FUZZ=0 leaves it out). Extra
# arguments go to ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
status=0
(cd "${BUILD_DIR:-$root/build}" && ctest --output-on-failure -j"$(nproc)" "$@") || status=$?
if [ "${LITAMIN2_RUN_FUZZ:-1}" != 0 ]; then
  "$root/scripts/fuzz.sh" || status=$?
fi
exit "$status"
