#!/usr/bin/env bash
# render-grid for the body and the photo space: the grid PNG and every cell PNG exist, every
# cell shows something (not a flat colour) and no two cells are the same.
set -euo pipefail
APP=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
check() {  # check SPACE N
  local space=$1 n=$2
  "$APP" render-grid --space "$space" --cell 96 --cells-dir "$T/$space" --cells-csv "$T/$space.csv" \
    -o "$T/$space.png"
  [[ -s "$T/$space.png" ]] || { echo "FAIL: no grid image for $space"; exit 1; }
  for ((r = 0; r < n; ++r)); do
    for ((c = 0; c < n; ++c)); do
      f="$T/$space/cell_${r}_${c}.png"
      [[ -s "$f" ]] || { echo "FAIL: missing $f"; exit 1; }
      convert "$f" -depth 8 rgb:"$T/$space/cell_${r}_${c}.rgb"
    done
  done
  [[ $(wc -l <"$T/$space.csv") -eq $((n * n + 1)) ]] || { echo "FAIL: $space.csv rows"; exit 1; }
  /usr/bin/python3 - "$T/$space" "$n" <<'PYEOF'
import sys, itertools
import numpy as np
folder, n = sys.argv[1], int(sys.argv[2])
cells = {}
for r in range(n):
    for c in range(n):
        a = np.fromfile(f"{folder}/cell_{r}_{c}.rgb", dtype=np.uint8).astype(np.int32)
        assert a.size == 96 * 96 * 3, a.size
        assert a.std() > 8, f"cell {r},{c} is flat (std {a.std():.1f})"
        cells[(r, c)] = a
worst = min(np.abs(cells[a] - cells[b]).mean() for a, b in itertools.combinations(cells, 2))
print(f"{folder}: {len(cells)} cells, smallest mean pairwise difference {worst:.2f}")
assert worst > 0.2, "two cells are identical"
PYEOF
}
check body 3
check photo 3
# The whole bodies on request: the same cells framed wider (the close-ups are the default).
"$APP" render-grid --space body --cell 96 --framing whole-body --cells-dir "$T/whole" \
  -o "$T/whole.png"
convert "$T/whole/cell_1_1.png" -depth 8 rgb:"$T/whole.rgb"
/usr/bin/python3 - "$T/body/cell_1_1.rgb" "$T/whole.rgb" <<'PYEOF'
import sys
import numpy as np
close, whole = (np.fromfile(f, dtype=np.uint8).astype(np.int32) for f in sys.argv[1:3])
diff = np.abs(close - whole).mean()
print(f"centre cell, close-up against whole body: mean difference {diff:.2f}")
assert diff > 2.0, "--framing whole-body drew the close-up"
PYEOF
# The kinds and their source options come from the catalogue; a wrong pair says which is which.
refused() {  # refused EXPECTED ARGS...
  local expected=$1; shift
  if out=$("$APP" render-grid -o "$T/refused.png" "$@" 2>&1); then
    echo "FAIL: render-grid $* was accepted"; exit 1
  fi
  grep -qF -- "$expected" <<<"$out" || { echo "FAIL: render-grid $*: $out"; exit 1; }
}
refused "--space must be body or photo" --space sound
refused "--model is for --space body; a photo search takes --image" --space photo --model male
refused "--image is for --space photo; a body search takes --model" --image "$T/x.png"
refused "--framing is close-ups or whole-body" --framing sideways
echo PASS
