#!/usr/bin/env bash
# ctest body_pkl_converter: builds a fake SMPL .pkl whose objects use chumpy's and scipy's class
# paths (fake modules exist only while pickling), converts it with tools/smpl_pkl_to_npz.py
# (which has neither), checks the arrays, and loads the result with the C++ loader.
# usage: pkl_converter_test.sh CONVERTER SEQUENTIAL_GALLERY WORK_DIR
set -euo pipefail
converter=$1 exe=$2 dir=$3
rm -rf "$dir"
mkdir -p "$dir/fake/chumpy" "$dir/fake/scipy/sparse"
cat >"$dir/fake/chumpy/__init__.py" <<'PY'
PY
cat >"$dir/fake/chumpy/ch.py" <<'PY'
class Ch(object):
    def __init__(self, x):
        self.x = x
PY
cat >"$dir/fake/scipy/__init__.py" <<'PY'
PY
cat >"$dir/fake/scipy/sparse/__init__.py" <<'PY'
PY
cat >"$dir/fake/scipy/sparse/csc.py" <<'PY'
import numpy as np
class csc_matrix(object):
    def __init__(self, dense):
        dense = np.asarray(dense)
        self._shape = dense.shape
        data, indices, indptr = [], [], [0]
        for c in range(dense.shape[1]):
            rows = np.nonzero(dense[:, c])[0]
            data.extend(dense[rows, c]); indices.extend(rows); indptr.append(len(data))
        self.data = np.array(data); self.indices = np.array(indices, dtype=np.int32)
        self.indptr = np.array(indptr, dtype=np.int32); self.format = "csc"; self.maxprint = 50
PY
PYTHONPATH="$dir/fake" /usr/bin/python3 - "$dir" <<'PY'
import pickle, sys
import numpy as np
from chumpy.ch import Ch
from scipy.sparse.csc import csc_matrix
d = sys.argv[1]
rng = np.random.default_rng(3)
# An octahedron-like closed mesh (6 vertices, 8 faces), 24 SMPL joints, 10 components.
v = np.array([[0, 1.8, 0], [0.2, 0.9, 0], [0, 0.9, 0.15], [-0.2, 0.9, 0], [0, 0.9, -0.15],
              [0, 0, 0]], dtype=np.float64)
f = np.array([[0, 2, 1], [0, 3, 2], [0, 4, 3], [0, 1, 4], [5, 1, 2], [5, 2, 3], [5, 3, 4],
              [5, 4, 1]], dtype=np.uint32)
J = 24
jr = np.zeros((J, 6)); jr[np.arange(J), np.arange(J) % 6] = 1.0
w = np.zeros((6, J)); w[np.arange(6), np.arange(6) * 3] = 1.0
parents = [4294967295, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21]
model = {
    "v_template": Ch(v), "shapedirs": Ch(rng.normal(0, 0.01, (6, 3, 10))),
    "posedirs": Ch(rng.normal(0, 0.01, (6, 3, 207))), "f": f,
    "J_regressor": csc_matrix(jr), "weights": Ch(w),
    "kintree_table": np.array([parents, list(range(J))], dtype=np.int64),
    "bs_style": "lbs", "bs_type": "lrotmin",
}
with open(d + "/fake_smpl.pkl", "wb") as fh:
    pickle.dump(model, fh, protocol=2)
np.savez(d + "/expected.npz", v_template=v, J_regressor=jr, weights=w,
         shapedirs=model["shapedirs"].x)
PY

# Convert without the fake modules on the path.
(cd "$dir" && /usr/bin/python3 "$converter" fake_smpl.pkl converted.npz)
/usr/bin/python3 - "$dir" <<'PY'
import sys
import numpy as np
d = sys.argv[1]
got, exp = np.load(d + "/converted.npz"), np.load(d + "/expected.npz")
for k in exp.files:
    assert np.array_equal(got[k], exp[k]), k
assert got["f"].dtype == np.uint32 and got["f"].shape == (8, 3)
assert "bs_style" not in got.files
print("converted arrays match")
PY
out=$("$exe" inspect --model "$dir/converted.npz")
echo "$out"
grep -q "usable  yes: 6 vertices, 8 faces, 24 joints (root 'pelvis'), 10 shape components" <<<"$out"
grep -Eq "height  1\.8000 m" <<<"$out"
echo "body_pkl_converter: ok"
