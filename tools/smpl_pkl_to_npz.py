#!/usr/bin/python3
"""Convert an official SMPL-family model .pkl (chumpy objects, scipy sparse J_regressor) to the
.npz layout Sequential Gallery loads, without needing chumpy or scipy installed.

    /usr/bin/python3 tools/smpl_pkl_to_npz.py basicModel_f_lbs_10_207_0_v1.0.0.pkl smpl_f.npz

The official files were pickled by Python 2 with chumpy arrays (class chumpy.ch.Ch and
friends) and a scipy.sparse csc_matrix. A custom Unpickler maps those classes to small
stand-ins that only keep their pickled state; the arrays are then taken from that state
(chumpy keeps its value in 'x', derived objects cache it in 'r') and sparse matrices are
densified from data/indices/indptr. Only numeric arrays are written; strings and other Python
objects are listed as skipped. Needs Debian's python3-numpy (use /usr/bin/python3).

Do not redistribute converted files: the SMPL-family licences forbid it (see README.md).
"""

import argparse
import pickle
import sys

try:
    import numpy as np
except ImportError:  # pragma: no cover - depends on the machine
    sys.exit("smpl_pkl_to_npz.py: numpy is missing; run it with /usr/bin/python3 "
             "(Debian package python3-numpy)")


class FakeChumpy:
    """Stand-in for any chumpy class: keeps the pickled state."""

    def __init__(self, *args, **kwargs):
        self.state = {}

    def __setstate__(self, state):
        if isinstance(state, tuple) and len(state) == 2:  # (dict, slots)
            state = state[0] or state[1]
        self.state = state if isinstance(state, dict) else {"x": state}

    def to_array(self):
        for key in ("x", "r"):  # a terminal keeps x; derived objects may cache r
            value = self.state.get(key)
            if value is not None:
                return to_array(value)
        raise ValueError("chumpy object without a stored value (keys: %s)"
                         % ", ".join(sorted(map(str, self.state))))


class FakeSparse:
    """Stand-in for scipy.sparse matrices (csc, csr, coo): densified from the pickled state."""

    kind = "csc"

    def __init__(self, *args, **kwargs):
        self.state = {}

    def __setstate__(self, state):
        self.state = state

    def to_array(self):
        s = self.state
        shape = tuple(int(n) for n in (s.get("_shape") or s.get("shape")))
        data = np.asarray(s["data"], dtype=np.float64)
        dense = np.zeros(shape, dtype=np.float64)
        if self.kind == "coo":
            row, col = np.asarray(s["row"]), np.asarray(s["col"])
            np.add.at(dense, (row, col), data)
            return dense
        indices, indptr = np.asarray(s["indices"]), np.asarray(s["indptr"])
        for major in range(len(indptr) - 1):
            lo, hi = int(indptr[major]), int(indptr[major + 1])
            if self.kind == "csc":  # columns are compressed
                dense[indices[lo:hi], major] += data[lo:hi]
            else:
                dense[major, indices[lo:hi]] += data[lo:hi]
        return dense


def sparse_class(kind):
    return type("Fake_%s_matrix" % kind, (FakeSparse,), {"kind": kind})


class ModelUnpickler(pickle.Unpickler):
    def find_class(self, module, name):
        if module == "chumpy" or module.startswith("chumpy."):
            return FakeChumpy
        if module.startswith("scipy.sparse"):
            for kind in ("csc", "csr", "coo"):
                if name.startswith(kind):
                    return sparse_class(kind)
            raise pickle.UnpicklingError("unsupported scipy.sparse class %s.%s" % (module, name))
        return super().find_class(module, name)


def to_array(value):
    if isinstance(value, (FakeChumpy, FakeSparse)):
        return value.to_array()
    return np.asarray(value)


def convert(src, dst, compress=True):
    with open(src, "rb") as f:
        try:
            data = ModelUnpickler(f, encoding="latin1").load()
        except Exception as e:  # noqa: BLE001 - report any unpickling problem clearly
            sys.exit("smpl_pkl_to_npz.py: %s: cannot unpickle: %s" % (src, e))
    if not isinstance(data, dict):
        sys.exit("smpl_pkl_to_npz.py: %s: expected a dict of arrays, found %s"
                 % (src, type(data).__name__))
    out, skipped = {}, []
    for key, value in data.items():
        try:
            arr = to_array(value)
        except Exception as e:  # noqa: BLE001
            skipped.append("%s (%s)" % (key, e))
            continue
        if arr.dtype.kind not in "fiub" or arr.dtype == object:
            skipped.append("%s (%s)" % (key, arr.dtype))
            continue
        out[str(key)] = arr
    missing = [k for k in ("v_template", "shapedirs", "f", "J_regressor", "weights",
                           "kintree_table") if k not in out]
    if missing:
        sys.exit("smpl_pkl_to_npz.py: %s: not an SMPL-family model, missing %s"
                 % (src, ", ".join(missing)))
    out["f"] = out["f"].astype(np.uint32)
    (np.savez_compressed if compress else np.savez)(dst, **out)
    for key in sorted(out):
        print("  %-20s %-8s %s" % (key, out[key].dtype, out[key].shape))
    if skipped:
        print("  skipped: " + ", ".join(skipped))
    print("wrote %s" % dst)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("pkl", help="official model .pkl (e.g. basicModel_f_lbs_10_207_0_v1.0.0.pkl)")
    p.add_argument("npz", help="output .npz")
    p.add_argument("--stored", action="store_true", help="write without compression")
    args = p.parse_args()
    convert(args.pkl, args.npz, compress=not args.stored)


if __name__ == "__main__":
    main()
