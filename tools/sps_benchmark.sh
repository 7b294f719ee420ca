#!/usr/bin/env bash
# Runs the paper's synthetic experiment (isotropic Gaussian 5-D/15-D, Rosenbrock 10-D/20-D,
# 25 iterations) for SPS, random-plane SPS and SLS with the argmax user and with the zoom user
# (3x3 grid, 4 levels), then writes docs/benchmarks.md next to the reference figures in
# ../shared/anchors/reference-sps/ (override with REFERENCE_DIR).
#
# Then the body benchmark (`simulate --function body`: the default model, 10 components, 3x3
# grid, 4 levels, a simulated person with a 5 mm just-noticeable difference, random targets,
# 15 planes) for SPS as the window runs it, SPS centred on the posterior-mean maximum, SPS
# without the perceptual hooks, random planes and SLS.
#
#   bash tools/sps_benchmark.sh            # 50 trials, as the paper (about 15-25 minutes)
#   TRIALS=10 bash tools/sps_benchmark.sh  # a quicker look
#   bash tools/sps_benchmark.sh --body     # only the body benchmark (BODY_TRIALS, default 20);
#                                          # the synthetic tables come from the CSVs on disk
#   bash tools/sps_benchmark.sh --report   # only re-write docs/benchmarks.md from those CSVs
set -euo pipefail
ONLY_BODY=0
REPORT_ONLY=0
[ "${1:-}" = "--body" ] && ONLY_BODY=1
[ "${1:-}" = "--report" ] && ONLY_BODY=1 && REPORT_ONLY=1
cd "$(dirname "$0")/.."
TRIALS=${TRIALS:-50}
BODY_TRIALS=${BODY_TRIALS:-20}
BIN=${BIN:-build/sequential-gallery}
OUT=${OUT:-docs/benchmarks}
REFERENCE_DIR=${REFERENCE_DIR:-../shared/anchors/reference-sps}
[ -x "$BIN" ] || { echo "build first: bash tools/build.sh (looked for $BIN)"; exit 1; }
mkdir -p "$OUT"
[ -d "$REFERENCE_DIR" ] || { echo "no reference figures in $REFERENCE_DIR (set REFERENCE_DIR)"; exit 1; }

settings=("gaussian 5" "gaussian 15" "rosenbrock 10" "rosenbrock 20")
if [ "$ONLY_BODY" = 0 ]; then
for user in argmax zoom; do
  for s in "${settings[@]}"; do
    set -- $s
    for method in sps sps-random sls; do
      name="$1-$2d_${method}_${user}"
      echo "== $name"
      "$BIN" simulate --function "$1" --dims "$2" --method "$method" --user "$user" \
        --trials "$TRIALS" --iterations 25 --seed 1000 --quiet \
        --csv "$OUT/$name.csv" --per-trial-csv "$OUT/${name}_per-trial.csv" > /dev/null
    done
  done
done
# Our extension: the zoom user's intermediate clicks as extra preference data.
for s in "${settings[@]}"; do
  set -- $s
  name="$1-$2d_sps-zoomprefs_zoom"
  echo "== $name"
  "$BIN" simulate --function "$1" --dims "$2" --method sps --user zoom --zoom-prefs \
    --trials "$TRIALS" --iterations 25 --seed 1000 --quiet \
    --csv "$OUT/$name.csv" --per-trial-csv "$OUT/${name}_per-trial.csv" > /dev/null
done
fi
# The body benchmark. "sps-plain": the session without the body's perceptual distance and
# scale (fixed factor-2 zoom, the paper's planes); "sps-mean-centre": planes centred on the
# posterior-mean maximum instead of the estimate of the body in mind; "sps-diagonal": one
# perceptual scale per component instead of the full metric.
for variant in sps sps-diagonal sps-mean-centre sps-plain sps-random sls; do
  [ "$REPORT_ONLY" = 1 ] && break
  name="body-10c_${variant}_zoom-jnd"
  method=${variant%-plain}
  method=${method%-mean-centre}
  method=${method%-diagonal}
  extra=()
  [ "$variant" = sps-plain ] && extra=(--no-adapt --no-perceptual-scale)
  [ "$variant" = sps-mean-centre ] && extra=(--no-target-model)
  [ "$variant" = sps-diagonal ] && extra=(--diagonal-metric)
  echo "== $name"
  "$BIN" simulate --function body --components 10 --method "$method" --user zoom-jnd \
    --jnd-mm 5 --grid 3 --levels 4 --trials "$BODY_TRIALS" --iterations 15 --seed 1000 --quiet \
    "${extra[@]}" --csv "$OUT/$name.csv" --per-trial-csv "$OUT/${name}_per-trial.csv" > /dev/null
done
# Re-writing the report alone: the trial counts are those of the CSVs on disk (distinct trial
# numbers of a per-trial file), not this run's defaults.
trials_in() { [ -f "$1" ] && tail -n +2 "$1" | cut -d, -f1 | sort -u | wc -l; }
if [ "$REPORT_ONLY" = 1 ]; then
  BODY_TRIALS=$(trials_in "$OUT/body-10c_sps_zoom-jnd_per-trial.csv" || echo "$BODY_TRIALS")
  TRIALS=$(trials_in "$OUT/gaussian-15d_sps_zoom_per-trial.csv" || echo "$TRIALS")
fi
new_doc=$(mktemp)
/usr/bin/python3 tools/sps_benchmark_report.py "$OUT" "$REFERENCE_DIR" "$TRIALS" "$BODY_TRIALS" > "$new_doc"
# The holds, pixel-person, loader and photo sections belong to tools/holds_benchmark.sh,
# tools/pixel_person_benchmark.sh, tools/loader_benchmark.sh and tools/photo_benchmark.sh:
# carried over as they are.
/usr/bin/python3 - docs/benchmarks.md "$new_doc" <<'PY'
import sys
old_path, new_path = sys.argv[1], sys.argv[2]
try:
    old = open(old_path).read()
except FileNotFoundError:
    old = ""
new = open(new_path).read()
# The sections other scripts write are carried over as they are.
for name in ("holds", "pixel", "loader", "photo"):
    begin, end = "<!-- %s-begin" % name, "<!-- %s-end -->" % name
    if begin in old and end in old and begin not in new:
        block = old[old.index(begin):old.index(end) + len(end)]
        new = new.rstrip("\n") + "\n\n" + block + "\n"
open(new_path, "w").write(new)
PY
mv "$new_doc" docs/benchmarks.md
echo "wrote docs/benchmarks.md"
