#!/usr/bin/env bash
# `cmake --install` into scratch DESTDIRs with prefix /usr (the package layout) and /usr/local
# (the default): binaries, config, Fast DDS profiles, units whose paths follow the prefix,
# sysctl/sysusers drop-ins; the installed units verify against the installed binaries and the
# installed litamin2d accepts the installed default config (--check-config).
# Usage: deploy_install.sh SOURCE_DIR BUILD_DIR WORK_DIR [BINARY...]
set -uo pipefail
src=$1; build=$2; work=$3; shift 3
bins=("$@")
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
have() { [[ -e $1 ]] || fail "missing ${1#"$dest"}"; }

for prefix in /usr /usr/local; do
  dest="$work/root${prefix//\//_}"
  if ! DESTDIR="$dest" cmake --install "$build" --prefix "$prefix" > "$dest.log" 2>&1; then
    fail "cmake --install --prefix $prefix: $(grep -m1 -A3 "Error" "$dest.log")"; continue
  fi
  if [[ $prefix == /usr ]]; then confdir=/etc/litamin2; else confdir=$prefix/etc/litamin2; fi
  for b in "${bins[@]}"; do
    [[ -x $dest$prefix/bin/$b ]] || fail "$prefix: $b not installed"
  done
  for f in "$src"/config/*.yaml; do have "$dest$confdir/$(basename "$f")"; done
  for f in "$src"/config/dds/*.xml; do [[ -e $f ]] && have "$dest$confdir/dds/$(basename "$f")"; done
  have "$dest$prefix/lib/sysctl.d/60-litamin2.conf"
  have "$dest$prefix/lib/sysusers.d/litamin2.conf"
  for unit in "$src"/deploy/systemd/*.service; do
    name=$(basename "$unit"); installed="$dest$prefix/lib/systemd/system/$name"
    have "$installed"; [[ -e $installed ]] || continue
    exec_line=$(grep '^ExecStart=' "$installed")
    exe=$(sed -E 's/^ExecStart=[-+!@:]*([^ ]+).*/\1/' <<<"$exec_line")
    [[ $exe == "$prefix/bin/"* ]] || fail "$prefix: $name runs $exe, not from $prefix/bin"
    if grep -q -- '--config ' <<<"$exec_line"; then
      conf=$(sed -E 's/.*--config ([^ ]+).*/\1/' <<<"$exec_line")
      [[ $conf == "$confdir/"* ]] || fail "$prefix: $name reads $conf, not from $confdir"
      # The shipped default config of a non-template unit is installed once it exists.
      if [[ $name != *@.service && -e $src/config/$(basename "$conf") ]]; then have "$dest$conf"; fi
    fi
    if [[ $prefix != /usr ]] && grep -qE '(^|[ =:])/usr/(bin|share)/' "$installed"; then
      fail "$prefix: $name still names /usr/bin or /usr/share"
    fi
    # Verify the installed unit against the installed binary (when that binary was built).
    if [[ -x $dest$exe ]] && command -v systemd-analyze >/dev/null; then
      mkdir -p "$dest.verify"; copy="$dest.verify/$name"
      sed "s#^ExecStart=\([-+!@:]*\)$exe#ExecStart=\1$dest$exe#" "$installed" > "$copy"
      target=$copy; [[ $name == *@.service ]] && target="$dest.verify/${name%@.service}@ci.service"
      out=$(systemd-analyze verify "$target" 2>&1); rc=$?
      if [[ $rc -ne 0 ]] || grep -qF -e "$dest.verify/" -e "${name%%@*}" <<<"$out"; then
        fail "$prefix: verify installed $name: $out"
      fi
    fi
  done
  # The installed daemon accepts the installed default config (what the unit will run).
  if [[ -x $dest$prefix/bin/litamin2d && -e $dest$confdir/litamin2d.yaml ]]; then
    out=$("$dest$prefix/bin/litamin2d" --check-config --config "$dest$confdir/litamin2d.yaml" 2>&1) \
      || fail "$prefix: litamin2d --check-config on the installed config: $out"
  fi
  echo "ok   install --prefix $prefix ($(find "$dest" -type f | wc -l) files)"
done

echo "$failures failed"
[[ $failures -eq 0 ]]
