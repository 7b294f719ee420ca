#!/usr/bin/env bash
# Loading an SMPL-X-sized model file: writes look-alike fixtures with the
# test fixture writer (10,475 vertices, 400 shape components, float64 arrays, 24 joints; no SMPL
# data), then times `inspect` and `measure --components 10 / 400` on them and prints wall time
# and peak RSS (best of RUNS). With a second binary (e.g. one built from an older commit) it
# measures both, as "before" and "after". numpy.load of the same files is timed for reference
# when python3 has numpy. Writes the "loader" section of docs/benchmarks.md.
#   usage: tools/loader_benchmark.sh [BUILD_DIR] [BEFORE_BINARY] [RUNS] [BEFORE_LABEL]
#   (defaults: build, none, 3, "BEFORE_BINARY"; BUILD_DIR needs sequential-gallery and
#   tests/body/body_fixture_writer: make -C build sequential-gallery body_fixture_writer)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
BEFORE=${2:-}
RUNS=${3:-3}
BEFORE_LABEL=${4:-$BEFORE}
APP=$BUILD/sequential-gallery
WRITER=$BUILD/tests/body/body_fixture_writer
for f in "$APP" "$WRITER" ${BEFORE:+"$BEFORE"}; do
  [ -x "$f" ] || { echo "loader_benchmark: $f is missing (build it first)" >&2; exit 1; }
done
WORK=$(mktemp -d "${TMPDIR:-/tmp}/sg_loader_bench.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

fixture=(plain --vertices 10475 --components 400 --float64)
"$WRITER" "$WORK/stored.npz" "${fixture[@]}" --stored
"$WRITER" "$WORK/deflated.npz" "${fixture[@]}"
"$WRITER" "$WORK/fortran.npz" "${fixture[@]}" --stored --fortran

# Prints "SECONDS MAX_RSS_MB" of one run of the command (its output is dropped; a failing
# command stops the benchmark).
measure_once() {
  if [ -x /usr/bin/time ]; then
    # time's own %e has 10 ms steps: the wall time is taken around it, in ns.
    local t0 t1
    t0=$(date +%s%N)
    /usr/bin/time -f '%M' -o "$WORK/time.txt" "$@" >/dev/null 2>"$WORK/err.txt" ||
      { cat "$WORK/err.txt" >&2; exit 1; }
    t1=$(date +%s%N)
    awk -v ns=$((t1 - t0)) '{printf "%.3f %.1f\n", ns / 1e9, $1 / 1024}' "$WORK/time.txt"
  else
    # getrusage of the child, through python3's resource module.
    /usr/bin/python3 - "$@" <<'PYEOF'
import resource, subprocess, sys, time
t = time.monotonic()
subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)
wall = time.monotonic() - t
print("%.3f %.1f" % (wall, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024))
PYEOF
  fi
}
# Best wall time and the peak RSS of that run, over RUNS runs.
measure_best() {
  local best="" line
  for _ in $(seq "$RUNS"); do
    line=$(measure_once "$@")
    if [ -z "$best" ] || awk -v a="$line" -v b="$best" 'BEGIN{split(a,x," ");split(b,y," ");exit !(x[1]<y[1])}'; then
      best=$line
    fi
  done
  echo "$best"
}

RESULTS=$WORK/results.tsv
: >"$RESULTS"
for file in stored deflated fortran; do
  for cmd in "inspect" "measure 10" "measure 400"; do
    case $cmd in
      inspect) args=(inspect --model "$WORK/$file.npz") ;;
      "measure 10") args=(measure --model "$WORK/$file.npz" --components 10) ;;
      "measure 400") args=(measure --model "$WORK/$file.npz" --components 400) ;;
    esac
    before="- -"
    [ -n "$BEFORE" ] && before=$(measure_best "$BEFORE" "${args[@]}")
    after=$(measure_best "$APP" "${args[@]}")
    printf '%s\t%s\t%s\t%s\n' "$file" "$cmd" "$before" "$after" | tee -a "$RESULTS"
  done
done

# numpy's reading of the same arrays, for reference (only if python3 has numpy).
NUMPY=$WORK/numpy.tsv
: >"$NUMPY"
if /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  for file in stored deflated fortran; do
    for what in shapedirs all; do
      code="import numpy; z = numpy.load('$WORK/$file.npz'); "
      if [ "$what" = shapedirs ]; then code+="a = z['shapedirs']"; else code+="a = [z[k] for k in z.files]"; fi
      printf '%s\t%s\t%s\n' "$file" "$what" "$(measure_best /usr/bin/python3 -c "$code")" | tee -a "$NUMPY"
    done
  done
fi

sizes=""
for file in stored deflated fortran; do
  sizes+="$file $(du -m "$WORK/$file.npz" | cut -f1) MB, "
done
PYTHONDONTWRITEBYTECODE=1 DOC_TOOLS="$ROOT/tools" /usr/bin/python3 - "$ROOT/docs/benchmarks.md" \
  "$RESULTS" "$NUMPY" "$RUNS" "${sizes%, }" "${BEFORE:+yes}" "$BEFORE_LABEL" <<'PYEOF'
import os, sys
sys.path.insert(0, os.environ["DOC_TOOLS"])
from doc_section import write_section
doc, results, numpy_tsv, runs, sizes, has_before, before_label = sys.argv[1:8]
what = {"stored": "C order, stored", "deflated": "C order, deflated",
        "fortran": "Fortran order, stored"}
command = {"inspect": "`inspect`", "measure 10": "`measure --components 10`",
           "measure 400": "`measure --components 400`"}
lines = [
    "<!-- loader-begin (tools/loader_benchmark.sh writes this section) -->",
    "## Loading an SMPL-X-sized model file",
    "",
    "`tools/loader_benchmark.sh build BEFORE " + runs + "`: look-alike fixtures written by the",
    "test fixture writer (`body_fixture_writer OUT plain --vertices 10475 --components 400",
    "--float64`, no SMPL data): 10,475 vertices, 400 shape components, float64 arrays, 24",
    "joints, no pose correctives (" + sizes + ").",
    "Wall time (s) and peak RSS (MB) of the whole command, best of " + runs + " runs with the",
    "file in the page cache (2 shared cores); `measure` includes its measurements (a fixed",
    "cost). With `--components K` the loader converts only K columns of `shapedirs`, straight",
    "into the model's matrix; `inspect` checks every value in one streaming pass and keeps one",
    "column. A deflated file is inflated whole whatever K is, so zlib's inflate bounds its times.",
    "",
]
if has_before:
    lines[-1:-1] = ["", "\"before\": " + before_label + "."]
if has_before:
    lines += ["| file | command | before s | before MB | after s | after MB |",
              "|---|---|---|---|---|---|"]
else:
    lines += ["| file | command | s | MB |", "|---|---|---|---|"]
for row in open(results):
    f, c, b, a = row.rstrip("\n").split("\t")
    cells = ([*b.split(), *a.split()] if has_before else a.split())
    lines.append("| " + what[f] + " | " + command[c] + " | " + " | ".join(cells) + " |")
numpy_rows = [r.rstrip("\n").split("\t") for r in open(numpy_tsv)]
if numpy_rows:
    lines += ["", "For reference, python3 with numpy (`numpy.load(FILE)['shapedirs']`, or every",
              "array), including the interpreter's start; the script times it only where",
              "`python3 -c 'import numpy'` works (Debian: python3-numpy):", "",
              "| file | numpy reads | s | MB |", "|---|---|---|---|"]
    for f, w, t in numpy_rows:
        lines.append("| " + what[f] + " | " + ("shapedirs" if w == "shapedirs" else "every array")
                     + " | " + " | ".join(t.split()) + " |")
else:
    lines += ["", "(numpy's figures are left out: python3 has no numpy here; install "
              "python3-numpy to compare.)"]
lines.append("<!-- loader-end -->")
write_section(doc, "loader", lines)
print("\n".join(lines))
PYEOF
