#!/usr/bin/env bash
# Regenerates the README's window screenshot (docs/screenshot.png): the body gallery on the
# default model, mid-session (one finished plane, two clicks on the second, a cell hovered),
# in a real window under Xvfb driven by xdotool.
#   bash tools/make_screenshot.sh [BUILD_DIR] [OUT.png] [extra gallery options...]
# HOVER_CELL=N hovers cell N (1-9) instead of 6. The holds screenshot (docs/screenshot-holds.png):
#   HOVER_CELL=4 bash tools/make_screenshot.sh build docs/screenshot-holds.png --hold height=1.80 --hold mass=85
set -euo pipefail
cd "$(dirname "$0")/.."
APP=${1:-build}/sequential-gallery
OUT=${2:-docs/screenshot.png}
shift 2 2>/dev/null || shift $#
[[ -x "$APP" ]] || { echo "make_screenshot: $APP not built (bash tools/build.sh)"; exit 1; }
if [[ -z "${DISPLAY:-}" ]]; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" bash "$0" "$(dirname "$APP")" "$OUT" "$@"
fi
T=$(mktemp -d)
trap 'kill $PID 2>/dev/null || true; rm -rf "$T"' EXIT
. tools/window_driver.sh
start_window "$APP" "$T" "$@"
planes() { /usr/bin/python3 -c "import json; print(len(json.load(open('$T/session.json'))['history']))" 2>/dev/null || echo 0; }
for c in 5 3 6 2; do click "$c"; done
for _ in $(seq 600); do [[ "$(planes)" == 1 ]] && break; sleep 0.1; done
sleep 1.5
click 7
click 5
xdotool mousemove --sync --window "$WIN" $(centre "${HOVER_CELL:-6}")
sleep 1
xdotool key F12
for _ in $(seq 100); do [[ -s "$T/shot.png" ]] && break; sleep 0.1; done
cp "$T/shot.png" "$OUT"
echo "wrote $OUT"
