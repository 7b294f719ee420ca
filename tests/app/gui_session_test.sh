#!/usr/bin/env bash
# Scripted session in a real window (run under xvfb-run): real mouse clicks with xdotool on the
# grid cells, two finished planes, a live window while the optimizer runs, Backspace undo,
# Ctrl+S glTF save, a kill -9 mid-session and a resume that finds every click.
# Usage: gui_session_test.sh /path/to/sequential-gallery
set -euo pipefail
APP=$1
source "$(dirname "$0")/gui_common.sh"
MODEL_ARGS=()
if [[ -n "${SG_GUI_TEST_MODEL:-}" ]]; then MODEL_ARGS=(--model "$SG_GUI_TEST_MODEL"); fi
PY=/usr/bin/python3

# session_field EXPR: evaluates a Python expression over the session JSON `s`.
session_field() {
  $PY -c "import json,sys; s=json.load(open('$T/session.json')); print($1)" 2>/dev/null || echo "?"
}
launch() {
  "$APP" gallery "${MODEL_ARGS[@]}" --session "$T/session.json" --save-path "$T/chosen.glb" \
    --window 1400x900 --zoom-seconds 0.4 --report-layout "$@" >>"$T/log" 2>&1 &
  APP_PID=$!
  wait_for_window
}
cell_centre() {  # cell_centre N -> "X Y" of grid cell N (1..9) from the app's layout report
  awk -v n="$1" '$1 == "[layout]" && $3 == n { printf "%d %d\n", $4 + $6 / 2, $5 + $6 / 2 }' \
    "$T/log" | tail -1
}
click_cell() {
  local xy
  xy=$(cell_centre "$1")
  [[ -n "$xy" ]] || fail "no layout for cell $1"
  # shellcheck disable=SC2086
  xdotool mousemove --sync --window "$WIN" $xy click 1
  # The zoom animation (0.4 s) plus frames to spare: a click during the animation is ignored
  # on purpose (it never counts as a second zoom step), so the next click must wait it out.
  sleep 1.0
}
clicks_on_plane() { [[ "$(session_field 'len(s["path"])')" == "$1" ]]; }
planes_done() { [[ "$(session_field 'len(s["history"])')" == "$1" ]]; }

echo "== launch (the optimizer is held back 4 s per plane to prove the window stays live)"
launch --resume no --optimizer-delay-ms 4000 --screenshot "$T/busy.png"

echo "== click, then Backspace undoes it"
click_cell 5
wait_for 5 clicks_on_plane 1 || fail "first click not recorded in the autosaved session"
xdotool key BackSpace
wait_for 5 clicks_on_plane 0 || fail "Backspace did not undo the click"
sleep 1.5  # the undo's zoom-out animation: clicks during it are ignored on purpose

echo "== plane 1: four real clicks"
for c in 1 6 8 3; do click_cell "$c"; done
echo "== while the optimizer runs, the window still answers (F12 screenshot)"
xdotool key F12
wait_for 3 test -s "$T/busy.png" || fail "no screenshot while the optimizer ran: UI blocked?"
planes_done 0 || fail "plane finished too early for the liveness check"
wait_for 60 planes_done 1 || fail "plane 1 not submitted (history $(session_field 'len(s["history"])'))"
wait_for 10 clicks_on_plane 0 || fail "plane 2 did not start"

echo "== plane 2: two clicks, then kill -9 mid-plane"
click_cell 9
click_cell 4
wait_for 5 clicks_on_plane 2 || fail "plane 2 clicks not autosaved"
kill -9 "$APP_PID"
wait "$APP_PID" 2>/dev/null || true
APP_PID=

echo "== relaunch and resume: nothing lost"
launch --resume yes
shown info "$T/session.json" || fail "the window did not say which session it resumed"
! shown_any error || fail "an error was shown"
[[ "$(session_field 'len(s["history"])')" == 1 ]] || fail "history lost on resume"
[[ "$(session_field 'len(s["path"])')" == 2 ]] || fail "zoom path lost on resume"
click_cell 2
click_cell 7
wait_for 60 planes_done 2 || fail "plane 2 not submitted"

echo "== Ctrl+S saves the current best body as glTF"
xdotool key ctrl+s
wait_for 20 test -s "$T/chosen.glb" || fail "Ctrl+S wrote no glTF"
$PY - "$T/chosen.glb" <<'PYEOF' || fail "saved file is not a valid GLB"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
magic, version, length = struct.unpack_from("<4sII", data, 0)
assert magic == b"glTF" and version == 2 and length == len(data), (magic, version, length)
chunk_len, chunk_type = struct.unpack_from("<I4s", data, 12)
assert chunk_type == b"JSON"
doc = json.loads(data[20:20 + chunk_len])
prim = doc["meshes"][0]["primitives"][0]
count = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
assert count > 100, count
print("glb ok:", len(data), "bytes,", count, "vertices")
PYEOF
wait_for 5 shown success "$T/chosen.glb" || fail "the saved file's path was not shown"

echo "== close the window; the session is saved"
kill "$APP_PID"
wait "$APP_PID" 2>/dev/null || true
APP_PID=
[[ "$(session_field 'len(s["history"])')" == 2 ]] || fail "final session lacks the two planes"
echo "PASS"
