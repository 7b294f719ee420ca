#!/usr/bin/env bash
# The grid of each zoom level of the first plane (or, with ZOOM_SKIP_PLANES=N, of plane N+1)
# in the real window at 1280x720 (Xvfb,
# xdotool), clicking the centre cell each time: docs/screenshot-zoom-levels.png, the four
# grids side by side as the window shows them (body cells about 230 px; with --space photo a
# 5x5 grid of about 136 px), to judge whether a person can tell every cell apart at each level.
#   bash tools/make_zoom_screenshots.sh [BUILD_DIR] [OUT.png] [extra gallery options...]
set -euo pipefail
cd "$(dirname "$0")/.."
APP=${1:-build}/sequential-gallery
OUT=${2:-docs/screenshot-zoom-levels.png}
shift 2 2>/dev/null || shift $#
[[ -x "$APP" ]] || { echo "make_zoom_screenshots: $APP not built (bash tools/build.sh)"; exit 1; }
if [[ -z "${DISPLAY:-}" ]]; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" bash "$0" "$(dirname "$APP")" "$OUT" "$@"
fi
T=$(mktemp -d)
trap 'kill $PID 2>/dev/null || true; rm -rf "$T"' EXIT
. tools/window_driver.sh
start_window "$APP" "$T" "$@"
# The grid's extent: from cell 1's corner to the last cell's far corner (9 or 25 cells).
last=$(awk '$1 == "[layout]" && $2 == "cell" { print $3 }' "$T/log" | sort -n | tail -1)
middle=$(((last + 1) / 2))
read -r x0 y0 < <(awk '$1 == "[layout]" && $2 == "cell" && $3 == 1 { print $4, $5 }' "$T/log" | tail -1)
read -r x1 y1 < <(awk -v n="$last" '$1 == "[layout]" && $2 == "cell" && $3 == n { print $4 + $6, $5 + $6 }' "$T/log" | tail -1)
shots=()
# Four grids: the zoom levels of the first plane, and when a plane ends early ("no visible
# change left") the next plane's first levels, each labelled with what it is.
plane=1
zoom=1
ends() { grep -c 'No visible change\|choice submitted' "$T/log" || true; }
# ZOOM_SKIP_PLANES=N: first click the centre cell through N planes, so that the grids shown
# are those of a later plane (the window's planes for a person start with the second).
for _ in $(seq "${ZOOM_SKIP_PLANES:-0}"); do
  before=$(ends)
  for _ in $(seq 8); do
    click "$middle"
    sleep 0.3
    [[ $(ends) -gt $before ]] && break
  done
  plane=$((plane + 1))
  sleep 2  # the next plane is computed
done
for level in 1 2 3 4; do
  rm -f "$T/shot.png"
  xdotool mousemove --sync --window "$WIN" 1270 700  # no cell hovered
  sleep 0.5
  xdotool key F12
  for _ in $(seq 100); do [[ -s "$T/shot.png" ]] && break; sleep 0.1; done
  sleep 0.3
  convert "$T/shot.png" -crop "$((x1 - x0))x$((y1 - y0))+$x0+$y0" +repage "$T/level$level.png"
  shots+=(-label "plane $plane, zoom level $zoom" "$T/level$level.png")
  if [[ $level -lt 4 ]]; then
    before=$(ends)
    click "$middle"
    sleep 0.3
    if [[ $(ends) -gt $before ]]; then
      plane=$((plane + 1))
      zoom=1
      sleep 2  # the next plane is computed
    else
      zoom=$((zoom + 1))
    fi
  fi
done
montage "${shots[@]}" -tile 4x1 -geometry +6+6 -pointsize 16 -background white "$OUT"
echo "wrote $OUT"
