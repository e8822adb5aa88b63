#!/usr/bin/env bash
# Checks the include rules of docs/architecture.md: which library folders may include which.
# Usage: architecture_includes.sh SOURCE_DIR. Prints every violation; exits 1 if there is one.
set -euo pipefail
root=$1
status=0
# folder (under src/ and include/litamin2/) -> the project folders it may include, and whether
# it may include yaml-cpp or Fast DDS / generated types.
check() {
  local folder=$1 allowed=$2 yaml=$3 dds=$4
  local files
  files=$(find "$root/src/$folder" "$root/include/litamin2/$folder" -maxdepth 1 -type f \
    \( -name '*.cpp' -o -name '*.hpp' \) 2>/dev/null || true)
  for f in $files; do
    while read -r inc; do
      [ -z "$inc" ] && continue
      local top=${inc%%/*}
      if ! [[ " $allowed " == *" $top "* ]]; then
        echo "$f: includes litamin2/$inc ($folder may include: $allowed)"; status=1
      fi
    done < <(grep -ho '#include "litamin2/[^"]*"' "$f" | sed 's|#include "litamin2/||; s|"||' |
             grep -v '^version.hpp$' || true)
    if [ "$yaml" = no ] && grep -q '#include <yaml-cpp' "$f"; then
      echo "$f: includes yaml-cpp (only src/config may)"; status=1
    fi
    if [ "$dds" = no ] && grep -qE '#include <fast(dds|rtps|cdr)/|#include "(sensor_msgs|nav_msgs|geometry_msgs|std_msgs|builtin_interfaces|diagnostic_msgs)/|#include "litamin2/msg/' "$f"; then
      echo "$f: includes Fast DDS or generated types (only dds and */dds may)"; status=1
    fi
  done
}
check core "core" no no
check io "core io" no no
check eval "core eval" no no
check service "service" no no
check metrics "service metrics" no no
check mapping "core mapping" no no
check store "core mapping store" no no
check sim "core io sim" no no
check daemon "core service daemon" no no
check aggregator "core io service mapping store aggregator" no no
check config "core mapping service daemon aggregator config" yes no
check dds "core service dds msg" no yes
check daemon/dds "core service dds msg daemon" no yes
check aggregator/dds "core service dds msg mapping aggregator" no yes
[ "$status" -eq 0 ] && echo "include rules of docs/architecture.md: ok"
exit "$status"
