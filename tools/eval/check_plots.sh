#!/usr/bin/env bash
# litamin2-eval --plot in its three formats, from KITTI and TUM input: each file is written,
# carries its format's signature and, for the SVG, the title, subtitle and axis text.
# Usage: check_plots.sh LITAMIN2_EVAL TESTDATA_DIR WORK_DIR
set -euo pipefail
eval_tool=$1; data=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
for ext in png svg pdf; do
  "$eval_tool" --gt "$data/gt_150.txt" --est "$data/est_150.txt" --plot "$work/kitti.$ext" > /dev/null
  [ -s "$work/kitti.$ext" ] || fail "no $ext written"
done
[ "$(head -c 8 "$work/kitti.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "not a PNG"
[ "$(head -c 5 "$work/kitti.pdf")" = "%PDF-" ] || fail "not a PDF"
grep -q "<svg" "$work/kitti.svg" || fail "not an SVG"
# Cairo writes text as glyphs; the SVG's glyph count shows text is there (title, ticks, legend).
glyphs=$(grep -c "<symbol\|glyph" "$work/kitti.svg" || true)
[ "$glyphs" -ge 20 ] || fail "SVG has only $glyphs glyph entries: no text?"
"$eval_tool" --format tum --t-max-diff 0.01 --gt "$data/gt_tum_150.txt" \
  --est "$data/est_tum_keyframes.txt" --plot "$work/keyframes.png" > /dev/null 2>&1
[ -s "$work/keyframes.png" ] || fail "no plot of the TUM keyframes"
echo "ok: png $(stat -c %s "$work/kitti.png") B, svg $(stat -c %s "$work/kitti.svg") B ($glyphs glyph lines), pdf $(stat -c %s "$work/kitti.pdf") B"
