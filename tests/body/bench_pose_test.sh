#!/usr/bin/env bash
# ctest body_bench_pose: the pose benchmark command (bench-pose) and `render --pose` on the
# fixture cylinders written by body_fixture_writer (SMPL's 24 joints and SMPL-X's 55, all on
# the cylinder's axis) and on the built-in female model: every pose gets a row, poses a model
# cannot make say why, models go side by side, the report and the sheet are written atomically.
# usage: bench_pose_test.sh SEQUENTIAL_GALLERY FIXTURE_WRITER WORK_DIR
set -euo pipefail
exe=$1 writer=$2 dir=$3
rm -rf "$dir"
mkdir -p "$dir"
"$writer" "$dir/cyl.npz"
"$writer" "$dir/cylx.npz" smplx

fail() { echo "FAIL: $*" >&2; exit 1; }
expect() {  # expect TEXT PATTERN
  grep -Eq -- "$2" <<<"$1" || fail "output does not match /$2/:
$1"
}
poses="shoulder-abduct-80 shoulder-abduct-170 shoulder-abduct-80-from-t
       shoulder-abduct-170-from-t shoulder-flex-90 elbow-130 forearm-twist-90 wrist-flex-60
       hip-flex-90 knee-130 head-turn-60 fist"

echo "== a file model: every pose a row, the fist not available without finger joints"
out=$("$exe" bench-pose --model "$dir/cyl.npz" --components 1 --out "$dir/cyl.md")
for p in $poses; do expect "$out" "^\| $p \|"; done
expect "$out" "^\| fist \| - \| - \| - \| n/a \|"
expect "$out" "fist: not available \(the skeleton has no left_index1"
expect "$out" "^\| \*\*passing\*\* \|"
expect "$out" "bodies: mean c1-3 c1\+3;"
cmp -s <(printf '%s\n' "$out" | head -n -2) "$dir/cyl.md" ||
  fail "--out differs from what was printed"

echo "== knuckles on one line: the palm is undefined, so no wrist flexion and no fist"
out=$("$exe" bench-pose --model "$dir/cylx.npz" --components 0)
expect "$out" "^\| wrist-flex-60 \| - \| - \| - \| n/a \|"
expect "$out" "fist: not available \(.*palm's direction is undefined"
expect "$out" "55 joints"

echo "== two models side by side, with labels"
out=$("$exe" bench-pose --model "$dir/cyl.npz" --label "old weights" --model female \
  --label new --components 1)
expect "$out" "^\| pose \| old weights: volume % \| fold deg \| self-int\. \| \| new: volume % \|"
row=$(grep -m1 -E '^\| elbow-130 \|' <<<"$out")  # the summary, not the per-body rows
[ "$(tr -cd '|' <<<"$row" | wc -c)" -eq 10 ] || fail "elbow-130 row has not 2 x 4 cells: $row"
expect "$out" "--label 'old weights'"  # the command, quoted so that it can be run again

echo "== the built-in female model, 7 bodies, in well under a minute"
start=$(date +%s)
out=$("$exe" bench-pose --model female)
secs=$(($(date +%s) - start))
echo "bench-pose --model female: $secs s"
[ "$secs" -lt 60 ] || fail "bench-pose --model female took $secs s"
expect "$out" "bodies: mean c1-3 c1\+3 c2-3 c2\+3 c3-3 c3\+3;"
# Numbers, not placeholders, on a pose every SMPL-family skeleton can make.
expect "$out" "^\| elbow-130 \| [-+][0-9]+\.[0-9] \([-+][0-9]+\.[0-9]\) \| [0-9]+ \([0-9]+\) \| [0-9]+ \([0-9.]+\) \| (pass|\*\*fail\*\*)"

echo "== --pose runs only the poses named; the others show as not run, without a reason line"
out=$("$exe" bench-pose --model "$dir/cyl.npz" --components 1 --pose elbow-130 --pose knee-130)
for p in elbow-130 knee-130; do  # measured: a fold and a count of intersections
  expect "$out" "^\| $p \| [^|]+ \| [0-9]+ \([0-9]+\) \| [0-9]+ \([0-9.]+\) \|"
done
expect "$out" "^\| shoulder-flex-90 \| - \| - \| - \| n/a \|"
expect "$out" "^\| \*\*passing\*\* \| \| \| \| [0-2] of 2 \|"
if grep -q "not asked for" <<<"$out"; then fail "the poses left out are listed as unavailable"; fi
if out=$("$exe" bench-pose --model "$dir/cyl.npz" --pose elbow-13 2>&1); then
  fail "bench-pose --pose elbow-13 succeeded"
fi
expect "$out" "'elbow-13' is not a pose of the benchmark \(its poses: shoulder-abduct-80, "

echo "== mistakes are named"
for bad in "--model $dir/missing.npz" "--model female --label a --label b" \
  "--model female --components 40" "--model female --sheet-model male" ""; do
  # shellcheck disable=SC2086
  if out=$("$exe" bench-pose $bad 2>&1); then fail "bench-pose $bad succeeded"; fi
  echo "ok: bench-pose $bad: $out"
done
out=$("$exe" bench-pose --model "$dir/missing.npz" 2>&1) || true
expect "$out" "missing\.npz"
out=$("$exe" bench-pose --model female --label a --label b 2>&1) || true
expect "$out" "2 --label for 1 --model"
out=$("$exe" bench-pose --model female --components 40 2>&1) || true
expect "$out" "the model 'female' has only [0-9]+ shape components"

echo "== a full disk leaves the old report as it was"
printf 'old report\n' >"$dir/full.md"
if out=$( (trap '' XFSZ; ulimit -f 4; "$exe" bench-pose --model female --components 0 \
  --out "$dir/full.md") 2>&1); then
  fail "bench-pose --out on a full disk succeeded"
fi
grep -qF "$dir/full.md" <<<"$out" || fail "the full-disk error does not name the report"
[ "$(cat "$dir/full.md")" = "old report" ] || fail "the old report was changed"

echo "== render --pose and the contact sheet"
help=$("$exe" render --help)
if grep -q -- "--pose" <<<"$help"; then
  for p in $poses; do expect "$help" "$p"; done
  "$exe" render --model female --pose elbow-130 --size 64x64 --samples 1 -o "$dir/elbow.png" |
    grep -q "pose elbow-130" || fail "render --pose: no mention of the pose"
  [ "$(head -c 4 "$dir/elbow.png" | tail -c 3)" = "PNG" ] || fail "elbow.png is not a PNG"
  out=$("$exe" render --model "$dir/cyl.npz" --pose fist -o "$dir/fist.png" 2>&1) &&
    fail "render --pose fist on a 24-joint model succeeded"
  expect "$out" "cannot make the pose fist: the skeleton has no left_index1"
  out=$("$exe" render --pose cartwheel -o "$dir/x.png" 2>&1) && fail "--pose cartwheel accepted"
  expect "$out" "unknown --pose 'cartwheel'; the poses are shoulder-abduct-80"
  out=$("$exe" render --pose fist --rest-pose t -o "$dir/x.png" 2>&1) &&
    fail "--pose with --rest-pose accepted"
  "$exe" bench-pose --model "$dir/cyl.npz" --label cyl --model female --label f \
    --components 0 --sheet "$dir/sheet.png" --sheet-model f --cell-size 64 >/dev/null
  [ "$(head -c 4 "$dir/sheet.png" | tail -c 3)" = "PNG" ] || fail "sheet.png is not a PNG"
  # 4 cells of 64 px and 4 px gaps across; one block (the --sheet-model's) of 3 rows under a
  # title, each cell with two label lines.
  width=$(od -An -tu1 -j16 -N4 "$dir/sheet.png" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}')
  height=$(od -An -tu1 -j20 -N4 "$dir/sheet.png" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}')
  [ "$width" -eq 276 ] || fail "sheet width $width, expected 4 x (64 + 4) + 4 = 276"
  [ "$height" -eq 362 ] || fail "sheet height $height, expected 4 + 28 + 3 x (64 + 42 + 4) = 362"
else
  out=$("$exe" bench-pose --model female --sheet "$dir/sheet.png" 2>&1) &&
    fail "--sheet without the renderer succeeded"
  expect "$out" "needs the renderer"
fi
echo "all bench-pose checks passed"
