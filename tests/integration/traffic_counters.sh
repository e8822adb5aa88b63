# Sourced by the standby tests and cost benchmarks (aggregator_standby.sh, aggregator_standby_cost.sh,
# daemon_standby_cost.sh):
# their Fast DDS profile, CPU ticks of a process, lo's transmit counters and UDP traffic per
# sender -> receiver.

# write_udp_lo_profile FILE [LEASE_S]: profile "litamin2", UDPv4 on 127.0.0.1 only (no shared
# memory, no multicast; unicast discovery to 127.0.0.1), with a participant lease of LEASE_S
# seconds (announced every 0.5 s) when given.
write_udp_lo_profile() {
  local lease=""
  [ -n "${2:-}" ] && lease="
          <discovery_config>
            <leaseDuration><sec>$2</sec></leaseDuration>
            <leaseAnnouncement><sec>0</sec><nanosec>500000000</nanosec></leaseAnnouncement>
          </discovery_config>"
  cat > "$1" <<XML
<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>udp_lo</transport_id>
        <type>UDPv4</type>
        <sendBufferSize>4194304</sendBufferSize>
        <receiveBufferSize>4194304</receiveBufferSize>
        <maxInitialPeersRange>16</maxInitialPeersRange>
        <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="litamin2">
      <rtps>
        <useBuiltinTransports>false</useBuiltinTransports>
        <userTransports><transport_id>udp_lo</transport_id></userTransports>
        <builtin>$lease
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
}

ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }  # ticks PID: utime + stime
# children_cpu_s FILE: user + system seconds of a subshell's children, from the last line of the
# bash `times` output written to FILE ("0m1.230s 0m0.450s"), to 0.01 s.
children_cpu_s() {
  tail -1 "$1" | tr 'ms' '  ' | awk '{printf "%.2f", $1 * 60 + $2 + $3 * 60 + $4}'
}
# lo's transmit counters from /proc/net/dev (this namespace's; /sys/class/net shows the
# namespace sysfs was mounted in): lo tx_packets | lo tx_bytes
lo() {
  awk -v f="$1" '$1 == "lo:" {print (f == "tx_packets" ? $11 : $10)}' /proc/net/dev
}
hz=$(getconf CLK_TCK)

# wait_quiet MAX_S PID...: returns when every PID used under 2 % of a core over the last second,
# or after MAX_S seconds.
wait_quiet() {
  local max=$1 prev=() quiet now i p
  shift
  for p in "$@"; do prev+=("$(ticks "$p")"); done
  for _ in $(seq 1 "$max"); do
    sleep 1
    quiet=1
    i=0
    for p in "$@"; do
      now=$(ticks "$p")
      [ $((now - prev[i])) -le $((hz / 50)) ] || quiet=0
      prev[i]=$now
      i=$((i + 1))
    done
    [ "$quiet" -eq 1 ] && return 0
  done
  return 0
}

traffic_matrix() {  # traffic_matrix DIR "PID=ROLE ..." [OTHER]: UDP payload MB and datagrams
  # per sender -> receiver from DIR/lo.pcap; a port is its owner's (DIR/sockets.txt), a process
  # not in the list is OTHER (default "publisher"), "?" a port no process listens on (discovery
  # sent to the unused ports of maxInitialPeersRange)
  tcpdump -r "$1/lo.pcap" -nn -q 2>/dev/null | python3 -c '
import collections, re, sys
roles = dict(r.split("=") for r in sys.argv[2].split())
owner = {}
for line in open(sys.argv[1] + "/sockets.txt"):
    m = re.search(r":(\d+)\s.*pid=(\d+)", line)
    if m:
        owner[m.group(1)] = roles.get(m.group(2), sys.argv[3])
sums = collections.defaultdict(lambda: [0, 0])
for line in sys.stdin:
    m = re.search(r"\.(\d+) > [\d.]+\.(\d+): UDP, length (\d+)", line)
    if not m:
        continue
    key = (owner.get(m.group(1), "?"), owner.get(m.group(2), "?"))
    sums[key][0] += int(m.group(3))
    sums[key][1] += 1
for (a, b), (n, d) in sorted(sums.items(), key=lambda kv: -kv[1][0]):
    print(f"{a} -> {b}: {n / 1e6:.2f} MB, {d} datagrams")
' "$1" "$2" "${3:-publisher}"
}
