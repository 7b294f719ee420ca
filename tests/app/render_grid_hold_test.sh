#!/usr/bin/env bash
# Holds through render-grid: every cell's measurements (--cells-csv) within the hold
# tolerance (1 cm for lengths, 1.5 kg for mass), every cell inside the box [0,1]^n, and the
# cells pairwise different as the window's look-alike test sees them (nearest_cell: the
# largest vertex distance to the nearest other cell, as the grid is framed). Tape measures
# are no proxy for that: on the survey-weighted models two held cells can differ by 10 cm
# in fat distribution and posture and by 3 mm in every girth. Bad holds are refused with a
# message.
set -euo pipefail
APP=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
check() {  # check NAME SEED HOLDS... (each "name=value")
  local name=$1 seed=$2
  shift 2
  local args=()
  for h in "$@"; do args+=(--hold "$h"); done
  # "height=1.72@" : aim for 1.72 with --target, then hold the bare name (the start's value).
  if [[ $1 == *@ ]]; then
    local h=${1%@}
    args=(--target "$h" --hold "${h%%=*}")
    set -- "$h" "${@:2}"
  fi
  "$APP" render-grid --seed "$seed" --cell 48 --samples 0 "${args[@]}" --cells-csv "$T/$name.csv" \
    -o "$T/$name.png"
  /usr/bin/python3 - "$T/$name.csv" "$@" <<'PYEOF'
import csv, itertools, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 9, len(rows)
tolerance = {"height": 0.01, "mass": 1.5}
held = {}
for h in sys.argv[2:]:
    k, v = h.split("=")
    held[k] = float(v)
column = {"height": "height_m", "mass": "mass_kg"}
worst = {k: 0.0 for k in held}
for r in rows:
    xs = [float(r[c]) for c in r if c.startswith("x")]
    assert len(xs) == 10 and min(xs) >= 0.0 and max(xs) <= 1.0, f"cell {r['row']},{r['col']} leaves the box: {xs}"
    for k, v in held.items():
        d = abs(float(r[column[k]]) - v)
        worst[k] = max(worst[k], d)
        assert d <= tolerance[k], f"cell {r['row']},{r['col']}: {k} {r[column[k]]} vs held {v}"
# The window's smallest difference between cells (app::ZoomPolicy::distinct_mm).
closest = min(float(r["nearest_cell"]) for r in rows)
assert closest >= 10.0, f"two cells look alike: only {closest:.1f} mm apart"
free = ["chest_m", "waist_m", "hips_m", "shoulder_width_m", "inseam_m", "arm_length_m"]
tape = min(max(abs(float(a[c]) - float(b[c])) for c in free) for a, b in itertools.combinations(rows, 2))
print(f"held {held}: worst deviation {worst}; closest pair {closest:.1f} mm apart "
      f"(the pair most alike in tape measures differs by {tape * 1000:.1f} mm)")
PYEOF
}
check tall 1 height=1.80
check tall2 7 height=1.80
check short_heavy 1 height=1.65 mass=90
check short_heavy2 3 height=1.65 mass=90
check target_then_hold 2 height=1.72@

refuse() {  # refuse PATTERN ARGS...
  local pattern=$1
  shift
  if out=$("$APP" render-grid --cell 32 -o "$T/bad.png" "$@" 2>&1); then
    echo "FAIL: accepted $*"
    exit 1
  fi
  grep -Eq -- "$pattern" <<<"$out" || { echo "FAIL: /$pattern/ not in: $out"; exit 1; }
}
refuse "unknown measurement 'weight'" --hold weight
refuse "height 'nan' is not a number" --hold height=nan
refuse "mass '1e9' is out of range" --hold mass=1e9
refuse "no measurements to hold" --space photo --hold height
# Holds no body in the search range meets were shown as nine copies of the nearest body.
refuse "out of reach.*nearest reachable: height" --hold height=0.5
refuse "out of reach.*nearest reachable: height" --hold height=3
refuse "out of reach.*nearest reachable: mass" --hold mass=500
refuse "out of reach.*nearest reachable: bmi" --hold bmi=90
# Height, mass and BMI that no body has together.
refuse "make a BMI of 11.1, not 40.0" --hold height=1.9 --hold mass=40 --hold bmi=40
refuse "is given twice" --hold height=1.8 --hold height=1.7
# A target on a held measurement must agree with the hold.
refuse "target height 170.0 cm contradicts the hold on height at 180.0 cm" \
  --hold height=1.8 --target height=1.7
# The window's command line is checked the same way, before a window opens.
if out=$("$APP" gallery --hold height=1.8 --target height=1.7 2>&1); then
  echo "FAIL: gallery accepted a target against a hold"
  exit 1
fi
grep -q "contradicts the hold on height" <<<"$out" || { echo "FAIL: gallery: $out"; exit 1; }
echo "render_grid_hold: all checks passed"
