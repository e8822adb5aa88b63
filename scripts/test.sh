#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (Release), runs every test under ctest
# (the fuzz harnesses among them, replaying their corpora: fuzz_replay_*), then the harnesses
# under libFuzzer with ASan/UBSan for FUZZ_SECONDS (default 20) each (scripts/fuzz.sh: clang, a
# build of its own in build-fuzz, ~7 min on 2 cores; LITAMIN2_RUN_FUZZ=0 leaves it out). Tests
# labelled build_variant (deploy_shared_install: a second whole build of the product, shared
# libraries, 10-20 min on 2 cores) run only with LITAMIN2_TEST_BUILD_VARIANTS=1. Extra
# arguments go to ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
status=0
variants=(-LE build_variant)
[ "${LITAMIN2_TEST_BUILD_VARIANTS:-0}" = 1 ] && variants=()
(cd "${BUILD_DIR:-$root/build}" && ctest --output-on-failure -j"$(nproc)" "${variants[@]}" "$@") ||
  status=$?
if [ "${LITAMIN2_RUN_FUZZ:-1}" != 0 ]; then
  "$root/scripts/fuzz.sh" || status=$?
fi
exit "$status"
