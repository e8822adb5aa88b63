#!/usr/bin/env bash
# A map patch announced larger than the payload limit (issue 14, docs/security.md "Later" ->
# "Fragmented samples"), in a private network namespace, UDP on 127.0.0.1 only (no shared
# memory: the pages of a writer's shared segment that a reader touches count in its RSS). A raw writer
# sends one valid 32 MB patch (800,000 distributions) to litamin2-aggregator with
# limits.max_distributions_per_patch 1000 (payload limit 1.04 MB), then a small patch:
#  - limits.fixed_patch_payloads false (default): Fast DDS reassembles the 32 MB sample, and
#    the CheckedType rejects it (patches_rejected.too_large 1): the aggregator's peak RSS
#    (VmHWM) grows by the sample's size (30.5 MiB; at least 29 MiB required);
#  - true: Fast DDS drops the sample before reserving it ("larger than the history payload
#    size" in the log), nothing reaches the listener, the peak RSS grows by less than 4 MiB.
# Both times the small patch is stored afterwards.
# Usage: patch_payload_bound.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
source "$(dirname "$0")/service_helpers.sh"
build=$1
work=$2
tools=$build/tools
probes=$build/tests/integration
domain=63
big=${BIG_DISTRIBUTIONS:-800000}  # 40 bytes each: 32 MB
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
  echo "FAIL: $*"
  [ -f aggregator.log ] && { echo "--- aggregator.log"; tail -n 30 aggregator.log; }
  exit 1
}
pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT
cat > udp.xml <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>udp</transport_id>
        <type>UDPv4</type>
        <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="udp">
      <rtps>
        <useBuiltinTransports>false</useBuiltinTransports>
        <userTransports><transport_id>udp</transport_id></userTransports>
        <builtin>
          <metatrafficUnicastLocatorList>
            <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
          </metatrafficUnicastLocatorList>
          <initialPeersList>
            <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
          </initialPeersList>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
XML
profile=$work/udp.xml:udp
hwm_kb() { awk '$1 == "VmHWM:" { print $2 }' "/proc/$1/status"; }

for fixed in false true; do
  mkdir "$fixed" && cd "$fixed"
  domain=$((domain + 1))
  cat > aggregator.yaml <<YAML
dds: {domain: $domain, profile: xml, xml_file: $work/udp.xml, xml_profile: udp}
store: {path: store.db}
publish: {poses_period_s: 0.2, summary_period_s: 1, status_period_s: 0.2}
watchdog: {enabled: false}
limits: {max_distributions_per_patch: 1000, fixed_patch_payloads: $fixed}
YAML
  "$tools/aggregator/litamin2-aggregator" --config aggregator.yaml > aggregator.log 2>&1 &
  aggregator_pid=$!
  pids+=("$aggregator_pid")
  "$probes/status_probe" --domain $domain --profile $profile \
    --topic rt/litamin2/aggregator/status --out aggregator_status.txt > status_a.log 2>&1 &
  pids+=($!)
  wait_status aggregator_status.txt litamin2-aggregator patches_rejected 0
  before=$(hwm_kb "$aggregator_pid")
  "$probes/raw_cdr_writer" --domain $domain --profile $profile --type patch --malformation valid \
    --count 1 --distributions $big --stream big_1 --timeout 15 > big.log 2>&1 ||
    { cat big.log; fail "the big patch's writer"; }
  sleep 0.5
  after=$(hwm_kb "$aggregator_pid")
  "$probes/raw_cdr_writer" --domain $domain --profile $profile --type patch --malformation valid \
    --count 1 --stream small_1 --timeout 15 > small.log 2>&1 || { cat small.log; fail "small"; }
  wait_status aggregator_status.txt small_1 keyframes 1
  growth=$(((after - before) / 1024))
  too_large=$(status_value aggregator_status.txt litamin2-aggregator patches_rejected.too_large)
  echo "fixed_patch_payloads $fixed: $(tail -n 1 big.log | cut -c1-90); peak RSS $((before / 1024)) -> $((after / 1024)) MiB (+$growth MiB) after the big patch, too_large ${too_large:-0}, small patch stored"
  if [ "$fixed" = false ]; then
    [ "$too_large" = 1 ] || fail "the big patch was not rejected as too_large"
    [ "$growth" -ge 29 ] || fail "peak RSS grew by $growth MiB only: the reassembly is not shown"
  else
    [ -z "$too_large" ] || [ "$too_large" = 0 ] || fail "the big patch reached the listener"
    grep -q "larger than the history payload size" aggregator.log ||
      fail "Fast DDS did not drop the sample at its history"
    [ "$growth" -lt 4 ] || fail "peak RSS grew by $growth MiB with fixed payloads"
  fi
  stop_services "$aggregator_pid"
  cd ..
done
echo PASS
