#!/usr/bin/env bash
# Runs the paper's synthetic experiment (isotropic Gaussian 5-D/15-D, Rosenbrock 10-D/20-D,
# 25 iterations) for SPS, random-plane SPS and SLS with the argmax user and with the zoom user
# (3x3 grid, 4 levels), then writes docs/benchmarks.md next to the reference figures in
# ../shared/anchors/reference-sps/ (override with REFERENCE_DIR).
#
#   bash tools/sps_benchmark.sh            # 50 trials, as the paper (about 15-25 minutes)
#   TRIALS=10 bash tools/sps_benchmark.sh  # a quicker look
set -euo pipefail
cd "$(dirname "$0")/.."
TRIALS=${TRIALS:-50}
BIN=${BIN:-build/sequential-gallery}
OUT=${OUT:-docs/benchmarks}
REFERENCE_DIR=${REFERENCE_DIR:-../shared/anchors/reference-sps}
[ -x "$BIN" ] || { echo "build first: bash tools/build.sh (looked for $BIN)"; exit 1; }
mkdir -p "$OUT"

settings=("gaussian 5" "gaussian 15" "rosenbrock 10" "rosenbrock 20")
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
/usr/bin/python3 tools/sps_benchmark_report.py "$OUT" "$REFERENCE_DIR" "$TRIALS" > docs/benchmarks.md
echo "wrote docs/benchmarks.md"
