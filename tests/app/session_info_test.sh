#!/usr/bin/env bash
# `sequential-gallery session-info` on a good session and on every broken fixture
# (tests/app/session_fixtures.cpp): the good one prints what it holds with exit 0; each broken
# one exits 1 naming the file and the problem -- never a crash, never an allocation bomb
# (ulimit -v: a multi-gigabyte allocation fails instead of swapping).
set -uo pipefail
tool=$1
writer=$2
dir=$3
rm -rf "$dir" && mkdir -p "$dir"
"$writer" "$dir" || { echo "FAIL: fixture writer"; exit 1; }
ulimit -v 4000000  # 4 GB of address space

failures=0
out=$("$tool" session-info "$dir/good.json" 2>&1)
rc=$?
echo "$out"
if [ $rc -ne 0 ]; then echo "FAIL: good session: exit $rc"; failures=$((failures + 1)); fi
for word in "components: 4" "planes: 3" "clicks on this plane: 1" "grid: 3x3" "version: 1"; do
  grep -qF "$word" <<<"$out" || { echo "FAIL: good session: '$word' missing"; failures=$((failures + 1)); }
done

count=0
for expected_file in "$dir"/*.expected; do
  name=$(basename "$expected_file" .expected)
  file="$dir/$name.json"
  expected=$(cat "$expected_file")
  out=$("$tool" session-info "$file" 2>&1)
  rc=$?
  count=$((count + 1))
  if [ $rc -ne 1 ]; then
    echo "FAIL: $name: exit $rc (want 1): $out"
    failures=$((failures + 1))
  elif ! grep -qF -- "$expected" <<<"$out" || ! grep -qF -- "$file" <<<"$out"; then
    echo "FAIL: $name: message lacks '$expected' or the file name: $out"
    failures=$((failures + 1))
  else
    echo "ok: $name: $out"
  fi
done

# A valid session whose model is gone: the window could not resume it either.
sed 's#"model_path": ""#"model_path": "/nonexistent/model.npz"#' "$dir/good.json" >"$dir/no-model.json"
out=$("$tool" session-info "$dir/no-model.json" 2>&1)
rc=$?
if [ $rc -ne 1 ] || ! grep -q "cannot load its body model.*nonexistent/model.npz" <<<"$out"; then
  echo "FAIL: session without its model: exit $rc: $out"
  failures=$((failures + 1))
else
  echo "ok: session without its model: $(tail -1 <<<"$out")"
fi

# Not a session at all: a folder, a missing file, an endless device.
for bad in "$dir" "$dir/missing.json" /dev/zero; do
  out=$("$tool" session-info "$bad" 2>&1)
  rc=$?
  if [ $rc -ne 1 ]; then echo "FAIL: $bad: exit $rc: $out"; failures=$((failures + 1)); else echo "ok: $bad: $out"; fi
done

echo "$count broken fixtures checked, $failures failure(s)"
[ "$count" -ge 20 ] || { echo "FAIL: too few fixtures"; exit 1; }
[ $failures -eq 0 ]
