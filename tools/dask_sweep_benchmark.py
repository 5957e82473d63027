#!/usr/bin/env python3
"""The Dask path of a dataset sweep (issue 31; not a test): N sampled variants of the
parametric four-bar with 360-row runs, their coupler curves streamed by
mechkin.sweep(client=..., out=..., curves=...) on a LocalCluster of W worker
processes (1 thread each) into part files merged into one HDF5 file; against the same
variants on local threads. Prints wall time, variants/s, the per-variant cost and the
merge's time. Usage: tools/dask_sweep_benchmark.py [N] [WORKERS] [CHUNK]"""
import json
import os
import random
import sys
import tempfile
import time

import distributed
import h5py
import numpy as np

import mechkin

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 4000
    workers = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    chunk = int(sys.argv[3]) if len(sys.argv) > 3 else None
    spec = json.load(open(os.path.join(HERE, "..", "mechanisms", "parametric-four-bar.json")))
    spec["analysis"]["steps"] = 359
    model = mechkin.loads(spec, "four-bar-360")
    rng = random.Random(1)
    ranges = {k: (v["min"], v["max"]) for k, v in model.parameter_info.items() if v["min"] is not None}
    variants = [{k: lo + (hi - lo) * rng.random() for k, (lo, hi) in ranges.items()} for _ in range(n)]
    curves = ["coupler_point.x", "coupler_point.y"]
    with tempfile.TemporaryDirectory() as tmp:
        start = time.time()
        local = mechkin.sweep(model, variants, out=os.path.join(tmp, "local"), curves=curves, threads=workers)
        t_local = time.time() - start
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            start = time.time()
            remote = mechkin.sweep(model, variants, client=client, out=os.path.join(tmp, "dask"), curves=curves,
                                   chunk=chunk)
            t_dask = time.time() - start
        with h5py.File(local) as a, h5py.File(remote) as b:
            same = all(np.array_equal(a[k][()], b[k][()], equal_nan=True) for k in ("curves", "status", "parameters"))
        parts = len([p for p in os.listdir(os.path.join(tmp, "dask")) if p.startswith("part-")])
    print("%d variants, %d workers: local threads %.1f s (%.0f variants/s), Dask LocalCluster %.1f s "
          "(%.0f variants/s, %d part files), per variant %.2f ms of a worker; same data: %s"
          % (n, workers, t_local, n / t_local, t_dask, n / t_dask, parts, 1000 * t_dask * workers / n, same))


if __name__ == "__main__":
    main()
