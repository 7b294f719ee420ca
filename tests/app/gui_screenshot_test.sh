#!/usr/bin/env bash
# Screenshot test (under xvfb-run): the app writes its own window to PNG; every grid cell must
# show a body (warm body pixels over the cool backdrop) and all nine cells must differ.
set -euo pipefail
APP=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
MODEL_ARGS=()
if [[ -n "${SG_GUI_TEST_MODEL:-}" ]]; then MODEL_ARGS=(--model "$SG_GUI_TEST_MODEL"); fi
timeout 120 "$APP" gallery "${MODEL_ARGS[@]}" --session "$T/session.json" --resume no \
  --window 1400x900 --report-layout --screenshot "$T/shot.png" --screenshot-after-frames 8 \
  --quit-after-screenshot >"$T/log" 2>&1 || { cat "$T/log"; echo "FAIL: app exited with error"; exit 1; }
[[ -s "$T/shot.png" ]] || { cat "$T/log"; echo "FAIL: no screenshot"; exit 1; }
convert "$T/shot.png" -depth 8 rgb:"$T/shot.rgb"
read -r W H < <(identify -format '%w %h\n' "$T/shot.png")
grep '^\[layout\] cell ' "$T/log" | awk '{print $3, $4, $5, $6}' >"$T/cells"
/usr/bin/python3 - "$T/shot.rgb" "$W" "$H" "$T/cells" <<'PYEOF'
import sys
import numpy as np
raw, w, h, cells_file = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
img = np.fromfile(raw, dtype=np.uint8).reshape(h, w, 3).astype(np.int32)
cells = {}
for line in open(cells_file):
    n, x, y, size = line.split()
    x, y, size = int(float(x)), int(float(y)), int(float(size))
    m = max(4, size // 20)  # stay inside the border and away from the label
    cells[int(n)] = img[y + m:y + size - m, x + m:x + size - m]
assert len(cells) == 9, f"expected 9 cells, layout reported {len(cells)}"
masks = {}
for n, c in sorted(cells.items()):
    body = (c[:, :, 0] - c[:, :, 2]) > 20  # skin-toned albedo: red well above blue
    share = body.mean()
    print(f"cell {n}: body pixels {100 * share:.1f}%  mean {c.mean():.1f}")
    assert share > 0.01, f"cell {n} looks empty"
    masks[n] = body
for a in range(1, 10):
    for b in range(a + 1, 10):
        diff = np.abs(cells[a] - cells[b]).mean()
        sil = (masks[a] != masks[b]).mean()
        assert diff > 0.3 or sil > 0.002, f"cells {a} and {b} look identical ({diff:.2f}, {sil:.4f})"
print("nine distinct, non-empty cells")
PYEOF
echo PASS
