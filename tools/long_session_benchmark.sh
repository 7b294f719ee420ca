#!/usr/bin/env bash
# The window on a fresh session and on one with 1 finished plane against one with PLANES
# finished planes (default 50), side by side: bench-gui on each, in turn, RUNS times (default
# 2). Prints, per session, the frame time while the camera orbits (it turns every frame), the
# click-to-frame time, the frame time of the zoom animations, launch to first grid and the
# start-up memory (peak RSS at the first grid), and how far the long session's mean is from the
# fresh and the one-plane session's. The sessions are made once, in-process, by bench-gui
# --write-session (the clicks go through the real controller, optimizer and autosave); each
# run resumes a copy.
#   bash tools/long_session_benchmark.sh [BUILD_DIR] [PLANES] [RUNS]   (starts Xvfb when needed)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
PLANES=${2:-50}
RUNS=${3:-2}
APP=$BUILD/sequential-gallery
[[ -x "$APP" ]] || { echo "long_session_benchmark: $APP not built"; exit 1; }
if [[ -z "${DISPLAY:-}" ]]; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" bash "$0" "$BUILD" "$PLANES" "$RUNS"
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# 3x3 cells of 180 px: a window that fits the 1280x720 screen.
COMMON=(bench-gui --cell-size 180 --clicks 12 --orbit-frames 90)
"$APP" "${COMMON[@]}" --write-session "$T/long.json" --planes-done "$PLANES" | tee "$T/make.log"
# One finished plane: what the long session is measured against as well. The fresh session's
# clicks are on the first plane, whose grid is made differently (the visible first plane), so
# fresh against long mixes the session's length with the first plane's content.
"$APP" "${COMMON[@]}" --write-session "$T/short.json" --planes-done 1 | tee -a "$T/make.log"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for run in $(seq 1 "$RUNS"); do
  "$APP" "${COMMON[@]}" >"$T/fresh-$run.txt" 2>&1
  "$APP" "${COMMON[@]}" --session "$T/short.json" >"$T/short-$run.txt" 2>&1
  "$APP" "${COMMON[@]}" --session "$T/long.json" >"$T/long-$run.txt" 2>&1
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
grep -h "^renderer:\|^grid:" "$T/fresh-1.txt"
/usr/bin/python3 - "$T" "$RUNS" "$PLANES" <<'PY'
import re, sys
folder, runs, planes = sys.argv[1], int(sys.argv[2]), sys.argv[3]
metrics = [
    ("orbit frame time median (ms)", r"orbit frames: \d+, frame time median: ([\d.]+)"),
    ("orbit frame time p95 (ms)", r"orbit frames: \d+, frame time median: [\d.]+ ms  p95: ([\d.]+)"),
    ("click to frame median (ms)", r"click to frame: \d+ clicks, median: ([\d.]+)"),
    ("click to frame max (ms)", r"click to frame: .* max: ([\d.]+)"),
    ("zoom click to frame median (ms)", r"zoom clicks: \d+, median: ([\d.]+)"),
    ("plane-ending click to frame median (ms)", r"plane-ending clicks: \d+, median: ([\d.]+)"),
    ("plane-ending clicks of 12", r"plane-ending clicks: (\d+)"),
    ("zoom frame time median (ms)", r"^frame time median: ([\d.]+)"),
    ("launch to first grid (ms)", r"launch to first grid: ([\d.]+)"),
    ("start-up peak RSS (MB)", r"start-up memory: peak RSS ([\d.]+)"),
]
def values(kind, pattern):
    out = []
    for run in range(1, runs + 1):
        text = open(f"{folder}/{kind}-{run}.txt").read()
        m = re.search(pattern, text, re.M)
        out.append(float(m.group(1)) if m else float("nan"))
    return out
print(f"| measure | fresh | 1 plane | {planes} planes | {planes} vs fresh | {planes} vs 1 plane (means) |")
print("|---|---|---|---|---|---|")
mean = lambda v: sum(v) / len(v)
gap = lambda a, b: (mean(a) - mean(b)) / mean(b) * 100 if mean(b) else float("nan")
fmt = lambda v: " / ".join(f"{x:.1f}" for x in v)
for name, pattern in metrics:
    fresh, short, long_ = (values(k, pattern) for k in ("fresh", "short", "long"))
    print(f"| {name} | {fmt(fresh)} | {fmt(short)} | {fmt(long_)} | {gap(long_, fresh):+.0f} % "
          f"| {gap(long_, short):+.0f} % |")
for run in range(1, runs + 1):
    for kind in ("fresh", "short", "long"):
        text = open(f"{folder}/{kind}-{run}.txt").read()
        if "click to frame" not in text:
            print(f"{kind} run {run} printed no result:\n{text[-2000:]}")
PY
