"""Runs a cgagen python kernel: drive.py META MODULE IN OUT64 OUT32 OUTSCALAR, or --bench N META MODULE.

META: {"name", "fn" and "prepare" (the functions as Python spells them), "inputs": [0 for a scalar, else the blade count], "uniform": [0/1 per input], "prepared": K,
"outputs": [blade counts]}; K > 0: a staged kernel, called as NAME(NAME_prepare(uniform inputs)[0], the
other inputs), NAME_prepare checked to return a tuple of one output of K values. IN has one
flat input row per line. The kernel is called once on whole arrays (float64, then float32: one call each, no
Python loop over samples) and on Python floats for the first 50 rows; results are written one flat row per
line. Checks the interface on the way: a tuple of outputs, each a tuple of the declared number of blades,
floats for float inputs, arrays of the input dtype for array inputs.
"""
import importlib.util
import json
import sys
import time

import numpy as np


def load(meta_path, module_path):
    meta = json.load(open(meta_path))
    spec = importlib.util.spec_from_file_location(meta["name"], module_path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    fn = getattr(mod, meta["fn"])
    if not meta.get("prepared"):
        return meta, fn
    prepare = getattr(mod, meta["prepare"])

    def staged(*args):
        uniform = [a for a, u in zip(args, meta["uniform"]) if u]
        element = [a for a, u in zip(args, meta["uniform"]) if not u]
        res = prepare(*uniform)
        assert isinstance(res, tuple) and len(res) == 1 and len(res[0]) == meta["prepared"], "prepare: %r" % (res,)
        return fn(list(res[0]), *element)

    return meta, staged


def split(meta, cols):
    args, off = [], 0
    for n in meta["inputs"]:
        if n == 0:
            args.append(cols[off])
            off += 1
        else:
            args.append([cols[off + k] for k in range(n)])
            off += n
    return args


def check_shape(meta, res, kind):
    assert isinstance(res, tuple) and len(res) == len(meta["outputs"]), "outputs: %r" % (res,)
    for out, n in zip(res, meta["outputs"]):
        assert isinstance(out, tuple) and len(out) == n, "output blades: %r" % (out,)
        for v in out:
            if kind is float:
                assert isinstance(v, float), type(v)
            else:
                assert isinstance(v, np.ndarray) and v.dtype == kind, (type(v), getattr(v, "dtype", None))


def flat(res):
    return [v for out in res for v in out]


def main():
    if sys.argv[1] == "--bench":
        n = int(sys.argv[2])
        meta, fn = load(sys.argv[3], sys.argv[4])
        width = sum(max(1, k) for k in meta["inputs"])
        data = np.random.default_rng(1).uniform(-1, 1, size=(width, n))
        args = split(meta, list(data))
        fn(*split(meta, list(data[:, :10])))  # warm up
        t0 = time.perf_counter()
        res = fn(*args)
        t1 = time.perf_counter()
        assert all(v.shape == (n,) for v in flat(res))
        print("%.3f" % ((t1 - t0) * 1e9 / n))
        return
    meta, fn = load(sys.argv[1], sys.argv[2])
    rows = np.loadtxt(sys.argv[3], ndmin=2)
    for dtype, path in ((np.float64, sys.argv[4]), (np.float32, sys.argv[5])):
        cols = list(rows.T.astype(dtype))
        res = fn(*split(meta, cols))
        check_shape(meta, res, dtype)
        np.savetxt(path, np.array(flat(res), dtype=np.float64).T, fmt="%.17g")
    with open(sys.argv[6], "w") as f:
        for row in rows[:50]:
            res = fn(*split(meta, [float(v) for v in row]))
            check_shape(meta, res, float)
            f.write(" ".join("%.17g" % v for v in flat(res)) + "\n")


main()
