#!/usr/bin/env bash
# The New-search panel's body model picker in a real window (run under xvfb-run), with real
# mouse clicks through xdotool on the positions the app reports (--report-layout):
# Female starts a female search (the session file records it), the choice reaches ui.json
# while the window is still open (it survives a kill -9), the next launch starts on it, a
# launch with --model overrides it without changing it, and a broken model file chosen in the
# in-app browser is refused by name with the search untouched.
# Usage: gui_model_picker_test.sh /path/to/sequential-gallery
set -euo pipefail
APP=$(realpath "$1")
source "$(dirname "$0")/gui_common.sh"
PY=/usr/bin/python3
json_field() {  # json_field FILE EXPR: a Python expression over the JSON `s`
  $PY -c "import json; s=json.load(open('$1')); print($2)" 2>/dev/null || echo "?"
}
is() { [[ "$(json_field "$1" "$2")" == "$3" ]]; }
launch() {  # launch SESSION_NAME [options...]
  local session=$1
  shift
  : >"$T/log"
  (cd "$T" && exec "$APP" gallery --session "$T/$session" --window 1600x1000 --file-dialog builtin \
    --zoom-seconds 0.3 --report-layout "$@" >>"$T/log" 2>&1) &
  APP_PID=$!
  wait_for_window
}
stop() {
  kill -9 "$APP_PID"
  wait "$APP_PID" 2>/dev/null || true
  APP_PID=
}
centre() {  # centre KIND NAME -> "X Y" of a reported cell or widget
  awk -v k="$1" -v n="$2" '$1 == "[layout]" && $2 == k && $3 == n {
    if (k == "cell") printf "%d %d\n", $4 + $6 / 2, $5 + $6 / 2;
    else printf "%d %d\n", $4 + $6 / 2, $5 + $7 / 2 }' "$T/log" | tail -1
}
click() {  # click KIND NAME
  local xy
  wait_for 5 grep -qs "^\[layout\] $1 $2 " "$T/log" || fail "no layout for $1 $2"
  xy=$(centre "$1" "$2")
  # shellcheck disable=SC2086
  xdotool mousemove --sync --window "$WIN" $xy click 1
  sleep 0.8
}

# The New-search tab shown.
echo '{"side_tab": "new-search"}' >"$T/ui.json"
cp "$T/ui.json" "$T/ui.initial"

echo "== first launch: neutral; choose Female and start a new search"
launch first.json --resume no
click cell 5
wait_for 5 is "$T/first.json" 'len(s["path"])' 1 || fail "the first click was not autosaved"
is "$T/first.json" 's["settings"]["model_path"]' neutral || fail "first launch is not on neutral"
click widget model:female
click widget new-search
click widget confirm:start
wait_for 10 is "$T/first.json" 's["settings"]["model_path"]' female ||
  fail "the new search is not on the female model: $(json_field "$T/first.json" 's["settings"]')"
is "$T/first.json" 'len(s["path"])' 0 || fail "the new search did not start fresh"
[[ -s "$T/first.json.previous" ]] || fail "the discarded search was not kept"
shown success female || fail "no message that the female model was opened"
echo "== ui.json records the choice while the window is open (then kill -9)"
wait_for 10 is "$T/ui.json" 's["body_model"]' female ||
  fail "ui.json not written after the change: $(cat "$T/ui.json")"
stop

echo "== next launch on a new session file: starts on female"
launch second.json --resume no
click cell 1
wait_for 5 is "$T/second.json" 'len(s["path"])' 1 || fail "no click autosaved on relaunch"
is "$T/second.json" 's["settings"]["model_path"]' female ||
  fail "relaunch not on the remembered model: $(json_field "$T/second.json" 's["settings"]')"
stop

echo "== --model male overrides it for one launch and is not remembered"
launch third.json --resume no --model male
click cell 1
wait_for 5 is "$T/third.json" 's["settings"]["model_path"]' male || fail "--model male ignored"
sleep 2
is "$T/ui.json" 's["body_model"]' female || fail "--model changed the remembered model"

echo "== a broken model file is refused by name; the search goes on untouched"
echo "not a model" >"$T/broken.npz"
click widget model:file  # no file yet: the in-app browser opens
click widget browser:name
xdotool type --delay 30 broken.npz
sleep 0.3
click widget browser:ok
click widget new-search
click widget confirm:start
wait_for 5 shown error "$T/broken.npz" ||
  fail "no error naming the broken file"
is "$T/third.json" 's["settings"]["model_path"]' male || fail "the search's model changed"
is "$T/third.json" 'len(s["path"])' 1 || fail "the search lost its click"
[[ ! -e "$T/third.json.previous" ]] || fail "the search was set aside for a file that failed"
sleep 2
is "$T/ui.json" 's["body_model"]' female || fail "a broken file was remembered"
stop
echo "PASS"
