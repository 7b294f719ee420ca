#!/usr/bin/env bash
# Start-up cost of the window on a fresh session against a long one: launch to first grid,
# time to 20 frames, and peak memory (max RSS). The long session is made first by the window
# itself (--benchmark-clicks, 48 planes of 4 clicks; planes that end early make it more).
#   bash tools/long_session_benchmark.sh [BUILD_DIR]     (starts its own Xvfb when needed)
set -euo pipefail
cd "$(dirname "$0")/.."
APP=$(realpath "${1:-build}")/sequential-gallery
[[ -x "$APP" ]] || { echo "long_session_benchmark: $APP not built"; exit 1; }
if [[ -z "${DISPLAY:-}" ]]; then
  exec xvfb-run -a -s "-screen 0 1600x1000x24" bash "$0" "$(dirname "$APP")"
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$APP" --session "$T/long.json" --resume no --benchmark-clicks 192 --zoom-seconds 0.05 \
  --window 1280x720 >"$T/make.log" 2>&1
planes=$(/usr/bin/python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['history']))" "$T/long.json")
echo "long session: $planes finished planes, $(stat -c %s "$T/long.json") bytes"
measure() {  # LABEL SESSION RESUME
  /usr/bin/python3 - "$APP" "$@" "$T/shot.png" <<'PY'
import resource, subprocess, sys, time
app, label, session, resume, shot = sys.argv[1:6]
start = time.time()
p = subprocess.run([app, "--session", session, "--resume", resume, "--window", "1280x720",
                    "--screenshot", shot, "--screenshot-after-frames", "20",
                    "--quit-after-screenshot"], capture_output=True, text=True)
seconds = time.time() - start
rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
first = [l for l in (p.stdout + p.stderr).splitlines() if l.startswith("first grid shown")]
print(f"{label}: {first[0] if first else 'no first grid'}; 20 frames and exit in "
      f"{seconds:.2f} s; max RSS {rss:.0f} MB")
PY
}
for run in 1 2; do
  rm -f "$T"/fresh.json*
  measure "fresh (run $run)" "$T/fresh.json" no
  cp "$T/long.json" "$T/copy.json"
  rm -f "$T"/copy.json.*
  measure "$planes planes (run $run)" "$T/copy.json" yes
done
