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
for word in "components: 4" "planes: 3" "clicks on this plane: 1" "grid: 3x3" "version: 1" \
  "current best: x = 0." "current best measures: height_m=1."; do
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
if [ $rc -ne 1 ] || ! grep -q "cannot open its body space.*nonexistent/model.npz" <<<"$out"; then
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

# Saved holds the window would refuse: session-info says the session is unusable as saved.
with_holds() {  # NAME HOLDS_JSON
  /usr/bin/python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); j["holds"]=json.loads(sys.argv[2]); json.dump(j,open(sys.argv[3],"w"))' \
    "$dir/good.json" "$2" "$dir/$1.json"
}
check_unusable() {  # NAME PATTERN
  out=$(timeout 60 "$tool" session-info "$dir/$1.json" 2>&1)
  rc=$?
  if [ $rc -ne 1 ] || ! grep -Eq -- "$2" <<<"$out"; then
    echo "FAIL: $1: exit $rc, /$2/ not in: $out"
    failures=$((failures + 1))
  else
    echo "ok: $1: $(tail -1 <<<"$out")"
  fi
}
with_holds holds-foo '[{"name": "foo", "value": 1.0}]'
check_unusable holds-foo "holds .*cannot be held: unknown measurement 'foo'"
with_holds holds-twice '[{"name": "height", "value": 1.7}, {"name": "height", "value": 1.8}]'
check_unusable holds-twice "cannot be held: height is given twice"
with_holds holds-out-of-reach '[{"name": "height", "value": 0.5}]'
check_unusable holds-out-of-reach "cannot be held: out of reach.*nearest reachable: height"
with_holds holds-good '[{"name": "height", "value": 1.7}]'
out=$("$tool" session-info "$dir/holds-good.json" 2>&1)
if ! grep -q "usable: yes" <<<"$out" || ! grep -q "holds: height 170.0 cm" <<<"$out"; then
  echo "FAIL: a session with a reachable hold: $out"
  failures=$((failures + 1))
else
  echo "ok: holds-good: $(grep holds: <<<"$out")"
fi

# Files that are not files: a FIFO as the session, or as a photo session's image, hung
# session-info (and the window) waiting for a writer.
mkfifo "$dir/fifo.json" "$dir/fifo.png"
check_unusable fifo "fifo.json: a pipe, not a regular file"
# The photo space opens its image through the same reader for session-info, the window and
# render-grid (a photo session needs 12 dimensions; render-grid opens the same space).
out=$(timeout 60 "$tool" render-grid --space photo --image "$dir/fifo.png" --cell 32 \
  -o "$dir/photo.png" 2>&1)
rc=$?
if [ $rc -ne 1 ] || ! grep -q "fifo.png: a pipe, not a regular file" <<<"$out"; then
  echo "FAIL: a FIFO as the photo: exit $rc: $out"
  failures=$((failures + 1))
else
  echo "ok: a FIFO as the photo: $out"
fi

echo "$count broken fixtures checked, $failures failure(s)"
[ "$count" -ge 20 ] || { echo "FAIL: too few fixtures"; exit 1; }
[ $failures -eq 0 ]
