#!/usr/bin/env bash
# Every man page generated from --help (tools/CMakeLists.txt, help2man) exists and has the
# sections a man page needs: NAME (with "tool \- summary", not help2man's "manual page for"
# placeholder), SYNOPSIS naming the tool, DESCRIPTION, and OPTIONS listing --version.
# Usage: check_man_pages.sh PAGE.N.gz...
set -euo pipefail
status=0
for page in "$@"; do
  before=$status
  file=$(basename "$page" .gz)
  tool=${file%.*}
  if [ ! -s "$page" ]; then echo "$page: missing"; status=1; continue; fi
  text=$(gzip -dc "$page")
  for section in NAME SYNOPSIS DESCRIPTION OPTIONS; do
    grep -q "^\.SH $section\$" <<< "$text" || { echo "$page: no $section section"; status=1; }
  done
  name_line=$(awk '/^\.SH NAME$/ {getline; print; exit}' <<< "$text")
  if [[ "$name_line" != "$tool \\- "?* ]] || [[ "$name_line" == *"manual page for"* ]]; then
    echo "$page: NAME line is '$name_line'"; status=1
  fi
  awk '/^\.SH SYNOPSIS$/ {getline; print; exit}' <<< "$text" | grep -qF "$tool" ||
    { echo "$page: SYNOPSIS does not name $tool"; status=1; }
  grep -q 'version' <<< "$(awk '/^\.SH OPTIONS$/,0' <<< "$text")" ||
    { echo "$page: OPTIONS do not list --version"; status=1; }
  [ "$status" -eq "$before" ] && echo "$page: ok ($name_line)"
done
exit "$status"
