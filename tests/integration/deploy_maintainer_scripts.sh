#!/usr/bin/env bash
# The Debian maintainer scripts (deploy/debian/) run for real, in a private mount namespace
# where /run, /var/lib and /etc/systemd/system are empty tmpfs and `systemctl` is a stub that
# records its arguments: every unit of deploy/systemd is stopped on removal and restarted on
# upgrade; purge removes the enablement links but keeps the aggregator's store unless
# LITAMIN2_PURGE_STATE=yes. Nothing outside the namespace is touched.
# Usage: deploy_maintainer_scripts.sh SOURCE_DIR WORK_DIR   (exit 77 = skipped: needs root)
set -uo pipefail
src=$(cd "$1" && pwd); work=$2
[[ $(id -u) -eq 0 ]] && command -v unshare >/dev/null \
  || { echo "SKIP: needs root and unshare for a private mount namespace"; exit 77; }
[[ -d /etc/systemd/system ]] || { echo "SKIP: no /etc/systemd/system to mount over"; exit 77; }
rm -rf "$work"; mkdir -p "$work/bin"
cat > "$work/bin/systemctl" <<STUB
#!/bin/sh
echo "\$*" >> "$work/systemctl.log"
STUB
# The user and sysctl steps must not touch this machine: stubs that record their call.
for tool in systemd-sysusers useradd sysctl; do
  printf '#!/bin/sh\necho "%s $*" >> "%s/system.log"\n' "$tool" "$work" > "$work/bin/$tool"
done
chmod +x "$work"/bin/*

units=()
for f in "$src"/deploy/systemd/*.service; do
  u=$(basename "$f"); units+=("${u/@.service/@*.service}")
done

unshare -m --propagation private bash -s "$src" "$work" "${units[@]}" <<'INNER'
set -uo pipefail
src=$1; work=$2; shift 2; units=("$@")
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
for d in /run /var/lib /etc/systemd/system; do mount -t tmpfs none "$d" || exit 1; done
mkdir -p /run/systemd/system /var/lib/litamin2 /etc/systemd/system/multi-user.target.wants
export PATH="$work/bin:$PATH"
log=$work/systemctl.log
calls() { : > "$log"; sh "$src/deploy/debian/$1" "${@:2}" || fail "$* exited $?"; }

calls prerm remove
for u in "${units[@]}"; do
  grep -q "^stop .*$u" "$log" || fail "prerm remove does not stop $u: $(cat "$log")"
done
calls prerm upgrade 1.0
[[ ! -s $log ]] || fail "prerm upgrade stops units: $(cat "$log")"
calls postinst configure 1.0  # upgrade from 1.0
for u in "${units[@]}"; do
  grep -q "^try-restart .*$u" "$log" || fail "postinst upgrade does not restart $u: $(cat "$log")"
done
calls postinst configure      # first install
grep -q "restart\|start\|enable" "$log" && fail "first install starts or enables: $(cat "$log")"

# purge: links go, the store stays unless asked.
echo store > /var/lib/litamin2/aggregator.db
for u in litamin2d.service litamin2d@a.service litamin2-aggregator.service; do
  ln -s /usr/lib/systemd/system/$u /etc/systemd/system/multi-user.target.wants/$u
done
calls postrm purge
left=$(ls /etc/systemd/system/multi-user.target.wants)
[[ -z $left ]] || fail "purge left enablement links: $left"
[[ -f /var/lib/litamin2/aggregator.db ]] || fail "purge removed the store without LITAMIN2_PURGE_STATE=yes"
LITAMIN2_PURGE_STATE=yes calls postrm purge
[[ ! -e /var/lib/litamin2 ]] || fail "purge with LITAMIN2_PURGE_STATE=yes kept /var/lib/litamin2"
echo "units checked: ${units[*]}"
echo "$failures failed"
[[ $failures -eq 0 ]]
INNER
