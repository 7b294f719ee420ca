# Sourced by the screenshot scripts: drives a real gallery window under Xvfb with xdotool.
# start_window APP DIR [gallery options...]: launches the window at 1280x720 on a fresh
# session in DIR, with its layout reported to DIR/log and F12 writing DIR/shot.png, and waits
# until the grid is laid out; sets PID and WIN (WINDOW_SIZE=WxH for another size). centre N:
# the centre of cell N (1-9) in window coordinates; click N: clicks it and lets the zoom
# finish; click_widget NAME: clicks a widget the window reported (e.g. tab:history).
start_window() {
  local app=$1 dir=$2
  shift 2
  XDG_STATE_HOME=$dir "$app" gallery --session "$dir/session.json" --window "${WINDOW_SIZE:-1280x720}" \
    --zoom-seconds 0.4 --report-layout --screenshot "$dir/shot.png" "$@" >"$dir/log" 2>&1 &
  PID=$!
  for _ in $(seq 300); do grep -qs '^\[layout\] cell 9 ' "$dir/log" && break; sleep 0.1; done
  WIN=$(xdotool search --sync --name '^Sequential Gallery$')
  WIN=${WIN%%$'\n'*} # the first window; not `| head -1`, which races with pipefail
  LAYOUT_LOG=$dir/log
  sleep 1
}
centre() {
  awk -v n="$1" '$1 == "[layout]" && $3 == n { printf "%d %d\n", $4 + $6 / 2, $5 + $6 / 2 }' \
    "$LAYOUT_LOG" | tail -1
}
click() { xdotool mousemove --sync --window "$WIN" $(centre "$1") click 1; sleep 1.2; }
click_widget() {
  local xy
  xy=$(awk -v n="$1" '$1 == "[layout]" && $2 == "widget" && $3 == n {
    printf "%d %d\n", $4 + $6 / 2, $5 + $7 / 2 }' "$LAYOUT_LOG" | tail -1)
  [[ -n "$xy" ]] || { echo "window_driver: no widget $1 reported"; return 1; }
  # shellcheck disable=SC2086
  xdotool mousemove --sync --window "$WIN" $xy click 1
  sleep 0.6
}
