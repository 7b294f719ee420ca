#!/usr/bin/env bash
# The pose benchmark of the built-in body models (`sequential-gallery bench-pose`): every pose
# of the pose library on each model's mean body and its +-3 SD bodies of components 1-3, with
# the volume change, sharpest fold and new self-intersections against the targets. Writes
# docs/pose-benchmark.md and the contact sheet docs/pose-benchmark.png (the current neutral
# model's mean body in every pose). Builds nothing: build sequential-gallery first.
#
# With BEFORE (a folder holding body_{female,male,neutral}.npz, or a git commit whose
# assets/body_*.npz are taken, e.g. the weights before a change), each built-in model is put
# beside its older self, labelled "<model> (BEFORE_LABEL)", so the gain is visible.
#   usage: tools/pose_benchmark.sh [EXECUTABLE] [BEFORE [BEFORE_LABEL]]
#   (defaults: ./build/sequential-gallery, none, the commit or "before")
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
APP=${1:-$ROOT/build/sequential-gallery}
BEFORE=${2:-}
BEFORE_LABEL=${3:-}
commit_used=
[ -x "$APP" ] || { echo "pose_benchmark: $APP is missing (build sequential-gallery first)" >&2; exit 1; }
if [ -n "$BEFORE" ] && [ ! -d "$BEFORE" ]; then
  # A commit: its models, read from git into a scratch folder.
  commit=$BEFORE
  commit_used=$commit
  BEFORE_LABEL=${BEFORE_LABEL:-$commit}
  BEFORE=$(mktemp -d "${TMPDIR:-/tmp}/sg_pose_bench.XXXXXX")
  trap 'rm -rf "$BEFORE"' EXIT
  for m in female male neutral; do
    git -C "$ROOT" show "$commit:assets/body_$m.npz" >"$BEFORE/body_$m.npz" ||
      { echo "pose_benchmark: no assets/body_$m.npz in commit $commit" >&2; exit 1; }
  done
fi
BEFORE_LABEL=${BEFORE_LABEL:-before}

args=()
for m in female male neutral; do
  if [ -n "$BEFORE" ]; then
    [ -f "$BEFORE/body_$m.npz" ] || { echo "pose_benchmark: $BEFORE/body_$m.npz is missing" >&2; exit 1; }
    args+=(--model "$BEFORE/body_$m.npz" --label "$m ($BEFORE_LABEL)")
  fi
  args+=(--model "$m" --label "$m")
done
cd "$ROOT"
start=$(date +%s)
# The sheet shows the default (neutral) model's mean body: the three models share the
# generator's weights, and 4 x 3 cells of 320 px keep the labels whole and the file ~1 MB.
"$APP" bench-pose "${args[@]}" --components 3 --out docs/pose-benchmark.md \
  --sheet docs/pose-benchmark.png --sheet-model neutral --cell-size 320
if [ -n "$commit_used" ]; then
  # The report names the scratch folder the older models were read into; say how to make it.
  sed -i "1,5s|^Made by \`.*\` (|Made by \`bash tools/pose_benchmark.sh build/sequential-gallery $commit_used\` (|" \
    docs/pose-benchmark.md
fi
echo "pose_benchmark: $(($(date +%s) - start)) s"
