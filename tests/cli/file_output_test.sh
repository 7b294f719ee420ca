#!/usr/bin/env bash
# Every file the tool writes goes through the one atomic writer (src/util/atomic_file.hpp):
# on a "full disk" (simulated with a file-size limit: the write fails with EFBIG instead of
# ENOSPC, same code path) the command fails, says so, and an existing file is untouched;
# no empty file is left. Also: long legal file names, and a folder given as -o.
# usage: file_output_test.sh SEQUENTIAL_GALLERY WORK_DIR [render]
set -uo pipefail
exe=$1 dir=$2 with_render=${3:-}
rm -rf "$dir" && mkdir -p "$dir"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Runs "$@" with writes limited to 4 KiB (ulimit -f counts 1 KiB blocks); SIGXFSZ is ignored
# (inherited through exec) so that write() returns EFBIG like a full disk returns ENOSPC.
full_disk() { (trap '' XFSZ; ulimit -f 4; "$@"); }

check_full_disk() {  # NAME COMMAND... (the command writes $dir/$NAME)
  local name=$1; shift
  local target="$dir/$name"
  "$@" -o "$target" >/dev/null || { fail "$name: the normal write failed"; return; }
  cp "$target" "$dir/$name.orig"
  out=$(full_disk "$@" -o "$target" 2>&1)
  rc=$?
  [ $rc -ne 0 ] || fail "$name: exit 0 on a full disk: $out"
  grep -q "wrote" <<<"$out" && fail "$name: says 'wrote' on a full disk: $out"
  grep -qF "$target" <<<"$out" || fail "$name: the error does not name the file: $out"
  cmp -s "$target" "$dir/$name.orig" || fail "$name: the old file was changed"
  rm -f "$dir/new-$name"
  full_disk "$@" -o "$dir/new-$name" >/dev/null 2>&1
  [ -e "$dir/new-$name" ] && fail "$name: a new file was left on a full disk ($(stat -c %s "$dir/new-$name") bytes)"
  leftovers=$(find "$dir" -name '.*tmp-*' | wc -l)
  [ "$leftovers" -eq 0 ] || fail "$name: $leftovers temporary files left behind"
  echo "ok: $name on a full disk: $out"
}

check_full_disk body.glb "$exe" export --betas 1 -1
if [ "$with_render" = render ]; then
  check_full_disk body.png "$exe" render --size 96x96 --samples 1
fi

if [ "$with_render" = render ]; then
  check_full_disk grid.png "$exe" render-grid --cell 32 --samples 0
  # The cells' CSV goes through the atomic writer too: it said "wrote" and left 0 bytes.
  "$exe" render-grid --cell 32 --samples 0 --cells-csv "$dir/cells.csv" -o "$dir/g.png" >/dev/null ||
    fail "render-grid --cells-csv: the normal write failed"
  cp "$dir/cells.csv" "$dir/cells.csv.orig"
  # A 1 KiB limit: the CSV (about 2 KB) is the first file to hit it.
  out=$( (trap '' XFSZ; ulimit -f 1; "$exe" render-grid --cell 32 --samples 0 \
    --cells-csv "$dir/cells.csv" -o "$dir/g2.png") 2>&1)
  rc=$?
  [ $rc -ne 0 ] || fail "render-grid --cells-csv: exit 0 on a full disk: $out"
  grep -q "wrote" <<<"$out" && fail "render-grid --cells-csv: says 'wrote' on a full disk: $out"
  grep -qF "$dir/cells.csv" <<<"$out" || fail "render-grid --cells-csv: error does not name the CSV: $out"
  cmp -s "$dir/cells.csv" "$dir/cells.csv.orig" || fail "render-grid --cells-csv: old CSV changed"
  echo "ok: render-grid --cells-csv on a full disk: $out"
  # A device as the target is refused, never renamed over (as root that replaced /dev/full).
  out=$("$exe" render-grid --cell 32 --samples 0 --cells-csv /dev/full -o "$dir/g3.png" 2>&1) &&
    fail "render-grid --cells-csv /dev/full succeeded: $out"
  grep -q "device, pipe or socket" <<<"$out" || fail "--cells-csv /dev/full: unclear: $out"
  [ -c /dev/full ] || fail "/dev/full is no longer a device"
  echo "ok: --cells-csv /dev/full: $out"
  for opt in --cells-csv --cells-dir; do
    out=$("$exe" render-grid --cell 32 $opt "" -o "$dir/g4.png" 2>&1) && fail "$opt '' accepted"
    grep -q -- "$opt is empty" <<<"$out" || fail "$opt '': unclear message: $out"
    echo "ok: $opt '': $out"
  done
fi

# A legal 250-byte file name: its temporary name must still fit in NAME_MAX (255).
long="$(printf 'b%.0s' $(seq 1 246)).glb"
out=$("$exe" export -o "$dir/$long" 2>&1) || fail "250-character file name: $out"
[ -s "$dir/$long" ] && echo "ok: 250-character file name"

# A folder as the output: say so (not "unknown extension ''").
mkdir -p "$dir/folder.glb"
for target in "$dir" "$dir/folder.glb"; do
  out=$("$exe" export -o "$target" 2>&1) && fail "export -o folder $target succeeded"
  grep -q "folder" <<<"$out" || fail "export -o folder: unclear message: $out"
  echo "ok: export -o $target: $out"
done

[ $failures -eq 0 ] && echo "all file-output checks passed"
[ $failures -eq 0 ]
