#!/usr/bin/env bash
# The body benchmark with a person who sees what the window shows:
# `simulate --function body --jnd-px 2 --cell-px N` for the default window's cell
# (230 px; the CSVs of the old layout's 210 px cells stay and are reported beside them) and a
# 400 px cell, SPS (the window's planes along where the estimate is least
# certain, and the paper's expected-improvement planes) against random planes and SLS, and SPS
# with a perfect chooser (`--jnd-mm 0`, the window's planes) for reference. Writes docs/benchmarks/pixel_*.csv and the "pixel person"
# section of docs/benchmarks.md (between its pixel-begin/pixel-end markers).
#   usage: tools/pixel_person_benchmark.sh [BUILD_DIR] [TRIALS] [PLANES]   (defaults: build 100 15;
#   20 trials rank settings by chance: the trajectories are chaotic)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
TRIALS=${2:-100}
PLANES=${3:-15}
APP=$BUILD/sequential-gallery
OUT=$ROOT/docs/benchmarks
mkdir -p "$OUT"
common=(simulate --function body --user zoom-jnd --components 10 --grid 3 --levels 4
        --trials "$TRIALS" --iterations "$PLANES" --seed 1000 --quiet)
start=$(date +%s)
# PIXEL_REPORT_ONLY=1: only re-write the section from the CSVs already in docs/benchmarks
# (after re-running one of them by hand with the command lines below; REPORT_NOTE, a sentence
# on which rows were re-run, replaces the generic one).
# The whole-body rows (pixel_*px-whole_*.csv) are kept from the previous build: re-run them with
# --framing whole-body by hand when the models change.
for cell in ${PIXEL_CELLS:-230 400}; do
  [ "${PIXEL_REPORT_ONLY:-0}" = 1 ] && break
  for method in sps sps-random sls; do
    "$APP" "${common[@]}" --method "$method" --jnd-px 2 --cell-px "$cell" \
      --csv "$OUT/pixel_${cell}px_${method}.csv" >/dev/null
  done
  "$APP" "${common[@]}" --method sps --plane-axes expected-improvement --jnd-px 2 \
    --cell-px "$cell" --csv "$OUT/pixel_${cell}px_sps-ei.csv" >/dev/null
done
[ "${PIXEL_REPORT_ONLY:-0}" = 1 ] ||
  "$APP" "${common[@]}" --method sps --jnd-mm 0 --csv "$OUT/pixel_perfect_sps.csv" >/dev/null
end=$(date +%s)
PYTHONDONTWRITEBYTECODE=1 DOC_TOOLS="$ROOT/tools" REPORT_ONLY="${PIXEL_REPORT_ONLY:-0}" /usr/bin/python3 - "$ROOT/docs/benchmarks.md" "$OUT" "$TRIALS" "$PLANES" $((end - start)) <<'PYEOF'
import csv, os, sys
sys.path.insert(0, os.environ["DOC_TOOLS"])
from doc_section import write_section, simulation_rows, optional_cell, mean_edge_cells
doc, out, trials, planes, seconds = sys.argv[1:6]
def rows(name):
    return simulation_rows(f"{out}/{name}.csv")
def row(label, r, dup):
    return (f"| {label} | {float(r[5]['mean_gap']):.2f} | {float(r[10]['mean_gap']):.2f} | "
            f"{float(r[15]['mean_gap']):.2f} | {float(r[10]['median_gap']):.2f} | "
            f"{float(r[15]['median_gap']):.2f} | {optional_cell(r, 10, 'median_saved_gap')} | "
            f"{mean_edge_cells(r)} | {dup} |")
perfect = rows("pixel_perfect_sps")
lines = [
    "<!-- pixel-begin (tools/pixel_person_benchmark.sh writes this section) -->",
    "## The pixel person: what the window's cells show",
    "",
    f"`tools/pixel_person_benchmark.sh build {trials} {planes}`: the body benchmark above with a",
    "person who sees how far each cell is from the body in mind as its largest visible shift",
    "(the largest vertex distance to the target, the measure the window's look-alike test uses",
    "between cells) and cannot tell apart cells whose shifts lie within what 2 px show in a",
    "cell of N px (`--jnd-px 2 --cell-px N`; the default cell camera shows 2.144 m, so 2 px",
    "are 18.6 mm at the default window's 230 px cells and 10.7 mm at 400 px). Each grid is",
    "framed to its tallest body, as the window frames it (`app::cell_frame_scale`: a grid of",
    "1.70 m people is shown 1.16 times larger). The estimate of the body in mind takes this",
    "person's choices as noisy as a third of the threshold (`app::choice_temperature_for_cells`:",
    "6.2 mm at 230 px, 3.6 at 400). The session uses the same threshold for its zoom (as the",
    "window does at that cell size) and as the planes' smallest side, and duplicate_grids",
    "counts grids with two cells closer than it.",
    "",
    "`sps` is what the window does for a person: planes along the two directions in which the",
    "estimate of the body in mind is least certain (`sps::PlaneAxes::kTargetUncertainty`: the",
    "principal axes of its covariance as a person sees it, the inverse of the choice model's",
    "Fisher information plus the population prior and what the choices' regions bound, with 8",
    "choice temperatures of slack; half-diagonals 5 standard deviations and at",
    "least twice the smallest side, and at least the side this person needs to tell the cells",
    "of a plane's last zoom level apart (`spaces::body_uncertainty_min_side`, since 2026-12-07:",
    "8 thresholds in RMS mm, a third of the framed threshold each; 30 mm at 230 px with",
    "close-ups, 50 on the whole body, 29 at 400 px on the whole body, and below the 24 mm",
    "of the smallest side at 400 px with close-ups), reaching beyond the box like random",
    "planes, with clamped cells kept apart: near a face of the box a plane is moved by whole",
    "cells, so that the estimate stays a cell of its first grid and the current best,",
    "`sps::Plane::best_s`, since the second run of 2026-12-07). `sps-ei` is the paper's plane",
    "(u towards x_EI, v by the plane's mean EI),",
    "which assumes a precise chooser. The reference row, a perfect chooser, has the window's",
    "planes: with the regions of its choices bounding the estimate they serve it best (mean gap",
    "at plane 10 4.97 mm against 6.96 on the paper's planes; before those regions it stalled at",
    "10.9 mm from plane 5 to 10 on the window's planes and used the paper's).",
    "Gap = RMS vertex distance (mm)",
    f"of the best body so far; {trials} trials (seeds 1000 onwards). \"closed\" = (random - SPS) /",
    "(random - perfect chooser) at plane 10, by mean. \"saved@10\": the median gap of what the",
    "window would save after plane 10 (its current best: the estimate of the body in mind, not",
    "the best pick, which only the benchmark knows); \"edge cells\": the share of the cells",
    "shown with a coefficient clamped at +-3 SD (mean over the planes); \"-\": not in the CSVs",
    "of older builds. The 210 px rows are the window's cells before the toolbar moved beside",
    "the grid (the old default; their CSVs are kept, not re-run).",
    "",
    "**Close-ups** (the window's default, its toolbar's View: Close-ups; `--framing close-ups`,",
    "the simulator's default): a grid whose bodies differ only below the head is framed from the",
    "top of its tallest head down to the lowest part of the body that moves at least 0.7 of the",
    "most any part moves across the grid (`body::GridFraming`, at least 1.0 m; to the floor",
    "once that reaches the shins), and what lies outside that band counts for nothing: the",
    "person and the look-alike test compare only what is in view, enlarged by the framing.",
    "After the first zoom most grids are framed from the thighs up, about 0.6 of the whole",
    "body's frame, so 2 px are about 11 mm of the trunk at 230 px, not 16-19. The planes'",
    "smallest side follows (the threshold times 0.6, `spaces::kCloseUpScale`). The \"whole",
    "body\" rows are made with `--framing whole-body` on the same models; when only the sps",
    "planes change, only the sps rows are re-run (the note below says which).",
    "",
    "| cell | method | mean gap@5 | mean gap@10 | mean gap@15 | median gap@10 | median gap@15 | saved@10 (median) | edge cells | look-alike grids (max share) |",
    "|---|---|---|---|---|---|---|---|---|---|",
]
closed = {}
# (file suffix, label): the close-ups the window shows now, and the whole-body framing of
# the previous build kept beside them (210 px: the old layout's cells).
for suffix, label in (("210px", "210 px, whole body"), ("230px-whole", "230 px, whole body"),
                      ("230px", "230 px, close-ups"), ("400px-whole", "400 px, whole body"),
                      ("400px", "400 px, close-ups")):
    if not os.path.exists(f"{out}/pixel_{suffix}_sps.csv"):
        continue
    data = {m: rows(f"pixel_{suffix}_{m}") for m in ("sps", "sps-ei", "sps-random", "sls")
            if os.path.exists(f"{out}/pixel_{suffix}_{m}.csv")}
    for m, r in data.items():
        dup = max(float(x["duplicate_grids"]) for x in r.values())
        lines.append(row(f"{label} | {m}", r, f"{dup:.3f}"))
    if "sps-random" in data:
        rnd, sps, best = (float(data["sps-random"][10]["mean_gap"]),
                          float(data["sps"][10]["mean_gap"]), float(perfect[10]["mean_gap"]))
        closed[label] = (rnd - sps) / (rnd - best) if rnd > best else float("nan")
lines.append(row("- | sps, perfect chooser (`--jnd-mm 0`)", perfect, "-"))
lines += ["", "Share of the gap between random planes and the perfect chooser that SPS closes at "
          f"plane 10: " + ", ".join(f"{v:.2f} at {k}" for k, v in closed.items()) +
          " (the issue asks for at least 0.5). " + (os.environ.get("REPORT_NOTE") or
                               "Section re-written from the CSVs after one of them was re-run."
                               if os.environ.get("REPORT_ONLY") == "1" else
                               f"Wall time {seconds} s (2 shared cores).")]
default = rows("pixel_230px_sps")
if "median_saved_gap" in default[1]:
    lines += ["", "What the window would save after plane 10 at 230 px (median) is "
              f"{float(default[10]['median_saved_gap']):.2f} mm from the body in mind, the last pick "
              f"{float(default[10]['median_last_pick_gap']):.2f} and the best pick so far "
              f"{float(default[10]['median_gap']):.2f}: the estimate averages the person's guesses "
              "between cells they cannot tell apart, so it is ahead of the last pick; the best "
              "pick is known only to the benchmark, which knows the target."]
lines += ["<!-- pixel-end -->"]
write_section(doc, "pixel", lines)
print("\n".join(lines))
PYEOF
