#!/usr/bin/env bash
# Screenshots of the window's side-panel tabs, in a real window under Xvfb driven by xdotool:
# the first grid (Measurements), a held search (height 1.80 m, mass 85 kg), the History tab
# after two finished planes, the Sliders, Save and New-search tabs; at one window size.
#   bash tools/make_panel_screenshots.sh [BUILD_DIR] [OUT_DIR] [WxH]
# writes OUT_DIR/panels-WxH-{first-grid,held,history,sliders,save,new-search}.png.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=${2:-/tmp/panel-shots}
SIZE=${3:-1280x720}
APP=$BUILD/sequential-gallery
[[ -x "$APP" ]] || { echo "make_panel_screenshots: $APP not built (bash tools/build.sh)"; exit 1; }
if [[ -z "${DISPLAY:-}" ]]; then
  exec xvfb-run -a -s "-screen 0 ${SIZE}x24" bash "$0" "$BUILD" "$OUT" "$SIZE"
fi
mkdir -p "$OUT"
export WINDOW_SIZE=$SIZE
. tools/window_driver.sh
shot() {  # shot NAME: F12, then copy the window's screenshot to OUT
  rm -f "$T/shot.png"
  xdotool key --window "$WIN" F12
  for _ in $(seq 100); do [[ -s "$T/shot.png" ]] && break; sleep 0.1; done
  cp "$T/shot.png" "$OUT/panels-$SIZE-$1.png"
  echo "wrote $OUT/panels-$SIZE-$1.png"
}
planes() {
  /usr/bin/python3 -c "import json; print(len(json.load(open('$T/session.json'))['history']))" \
    2>/dev/null || echo 0
}
finish_plane() {  # finish_plane N: four clicks, then waits until N planes are done
  for c in 5 3 6 2; do click "$c"; done
  for _ in $(seq 600); do [[ "$(planes)" == "$1" ]] && break; sleep 0.1; done
  sleep 1.5
}
session() {  # session [gallery options...]: a fresh window on a fresh session
  T=$(mktemp -d)
  start_window "$APP" "$T" --resume no "$@"
}
close() { kill "$PID" 2>/dev/null || true; wait "$PID" 2>/dev/null || true; rm -rf "$T"; }
trap 'close' EXIT

session
xdotool mousemove --sync --window "$WIN" $(centre 6)
sleep 1
shot first-grid
close

session --hold height=1.80 --hold mass=85
xdotool mousemove --sync --window "$WIN" $(centre 4)
sleep 1
shot held
close

session
finish_plane 1
finish_plane 2
click_widget tab:history
xdotool mousemove --sync --window "$WIN" 1 1
sleep 1
shot history
click_widget tab:sliders
shot sliders
click_widget tab:save
shot save
click_widget tab:new-search
click_widget model:male
sleep 0.5
shot new-search
close
