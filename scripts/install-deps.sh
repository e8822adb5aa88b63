#!/usr/bin/env bash
# Installs the Debian 12 packages the build and the tests need, only when some are missing.
# --fuzz: also clang and libFuzzer's runtime (scripts/fuzz.sh).
set -euo pipefail
pkgs=(build-essential cmake pkg-config libfastrtps-dev fastddsgen fastdds-tools cyclonedds-dev cyclonedds-tools libsystemd-dev systemd iproute2 util-linux libeigen3-dev libtbb-dev libyaml-cpp-dev libspdlog-dev
      libcli11-dev libnanoflann-dev robin-map-dev libembree-dev libgtest-dev libgmock-dev
      libbenchmark-dev libcairo2-dev libceres-dev libsqlite3-dev sqlite3 python3 python3-numpy python3-scipy file dpkg-dev
      libssl-dev openssl tcpdump liblzf-dev nlohmann-json3-dev libcpp-httplib-dev help2man curl)
if [ "${1:-}" = --fuzz ]; then pkgs+=(clang libclang-rt-14-dev); fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
