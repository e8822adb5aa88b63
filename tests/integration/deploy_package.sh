#!/usr/bin/env bash
# `cpack -G DEB` into a scratch folder, then the package is read with dpkg-deb: name, version,
# Depends computed by dpkg-shlibdeps, binaries, units, drop-ins, /etc/litamin2 as conffiles,
# executable maintainer scripts, units naming /usr/bin and /etc/litamin2, nothing in /usr/local,
# a man page per binary (man8 for the daemons, man1 for the tools).
# Usage: deploy_package.sh SOURCE_DIR BUILD_DIR WORK_DIR VERSION [BINARY...]   (exit 77 = skipped)
set -uo pipefail
src=$1; build=$2; work=$3; version=$4; shift 4
bins=("$@")
for tool in dpkg-deb dpkg-shlibdeps file; do
  command -v $tool >/dev/null || { echo "SKIP: $tool missing (packages dpkg-dev, file)"; exit 77; }
done
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# A plain `cpack` first builds the project (target preinstall); a test must not build, so the
# same install script runs through CPACK_INSTALL_SCRIPTS with the prefix the DEB generator uses:
# CPACK_PACKAGING_INSTALL_PREFIX, valid while CPACK_SET_DESTDIR is off (checked here).
grep -q '^set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")' "$build/CPackConfig.cmake" \
  || { echo "CPACK_PACKAGING_INSTALL_PREFIX is not /usr"; exit 1; }
grep -qE '^set\(CPACK_SET_DESTDIR "(OFF|FALSE|0|)"\)' "$build/CPackConfig.cmake" \
  || { echo "CPACK_SET_DESTDIR is on: the package would be rooted at CMAKE_INSTALL_PREFIX"; exit 1; }
printf 'set(CMAKE_INSTALL_PREFIX /usr)\ninclude("%s/cmake_install.cmake")\n' "$build" > "$work/install.cmake"
start=$SECONDS
if ! (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work" \
        -D CPACK_INSTALL_CMAKE_PROJECTS= -D CPACK_INSTALL_SCRIPTS="$work/install.cmake" \
        > cpack.log 2>&1); then
  echo "cpack failed:"; tail -20 "$work/cpack.log"; exit 1
fi
debs=("$work"/*.deb)
[[ ${#debs[@]} -eq 1 && -f ${debs[0]} ]] || { echo "expected one .deb, got: ${debs[*]}"; exit 1; }
deb=${debs[0]}
echo "ok   $(basename "$deb"), $(du -h "$deb" | cut -f1), built in $((SECONDS - start)) s"

field() { dpkg-deb -f "$deb" "$1"; }
[[ $(field Package) == litamin2 ]] || fail "Package: $(field Package)"
[[ $(field Version) == "$version" ]] || fail "Version: $(field Version), expected $version"
[[ $(field Depends) == *libc6* ]] || fail "Depends not computed by dpkg-shlibdeps: '$(field Depends)'"
[[ -n $(field Maintainer) ]] || fail "no Maintainer"
echo "ok   control: Depends: $(field Depends)"

dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' > "$work/files.txt"
has() { grep -qx -- "$1" "$work/files.txt" || fail "not in package: $1"; }
for b in "${bins[@]}"; do has "/usr/bin/$b"; done
# Man pages from --help (tools/CMakeLists.txt): section 8 for the daemons, 1 for the rest.
for b in "${bins[@]}"; do
  case $b in litamin2d | litamin2-aggregator) has "/usr/share/man/man8/$b.8.gz" ;;
    *) has "/usr/share/man/man1/$b.1.gz" ;; esac
done
for f in "$src"/deploy/systemd/*.service; do has "/usr/lib/systemd/system/$(basename "$f")"; done
has /usr/lib/sysctl.d/60-litamin2.conf
has /usr/lib/sysusers.d/litamin2.conf
for f in "$src"/config/*.yaml; do has "/etc/litamin2/$(basename "$f")"; done
for f in "$src"/config/dds/*.xml; do [[ -e $f ]] && has "/etc/litamin2/dds/$(basename "$f")"; done
if grep -q '^/usr/local' "$work/files.txt"; then fail "package installs into /usr/local"; fi

dpkg-deb -e "$deb" "$work/control"
for s in postinst prerm postrm; do [[ -x $work/control/$s ]] || fail "maintainer script $s missing or not executable"; done
grep '^/etc/litamin2/' "$work/files.txt" | grep -v '/$' | sort > "$work/etc_files.txt"
sort "$work/control/conffiles" 2>/dev/null | diff "$work/etc_files.txt" - > "$work/conffiles.diff" \
  || fail "conffiles differ from the /etc/litamin2 files: $(cat "$work/conffiles.diff")"

dpkg-deb -x "$deb" "$work/root"
for f in "$work"/root/usr/lib/systemd/system/*.service; do
  exe=$(sed -nE 's/^ExecStart=[-+!@:]*([^ ]+).*/\1/p' "$f")
  [[ $exe == /usr/bin/* ]] || fail "$(basename "$f"): ExecStart $exe"
  grep -q -- '--config /etc/litamin2/' "$f" || fail "$(basename "$f"): config not under /etc/litamin2"
  # Once the daemon is packaged, its default config must be packaged too.
  conf=$(sed -nE 's/^ExecStart=.*--config ([^ ]+).*/\1/p' "$f")
  if [[ -x $work/root$exe && $conf != *%i* && ! -e $work/root$conf ]]; then
    fail "$(basename "$f"): $conf is not in the package"
  fi
done
echo "ok   $(wc -l < "$work/files.txt") entries, $(wc -l < "$work/etc_files.txt") conffiles"

echo "$failures failed"
[[ $failures -eq 0 ]]
