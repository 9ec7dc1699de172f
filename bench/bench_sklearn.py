#!/usr/bin/python3
"""Side by side with scikit-learn's SpectralClustering on dresskit's own affinity.

usage: bench/bench_sklearn.py DIR [REPS]
DIR is what `bench_segmentation --export DIR` wrote: gc_affinity.mtx (the affinity of gc_mean_all),
gc_labels_plain.txt (dresskit's plain spectral clustering: normalised Laplacian, Spectra, k-means++,
no clean-up or merging), gc_plain_seconds.txt (its eigen + k-means time) and gc_labels_final.txt.
Prints scikit-learn's fit time (median of REPS, one thread), the time ratio and the label agreement
(fraction of vertices with the same label after the best one-to-one matching).
Needs Debian's python3-sklearn (apt-get install --no-install-recommends python3-sklearn); not used by
the build or the tests. Run it pinned to one core: taskset -c 0 bench/bench_sklearn.py DIR.
"""
import os
import sys

for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(var, "1")

import time  # noqa: E402

import numpy as np  # noqa: E402
import scipy.io  # noqa: E402
from scipy.optimize import linear_sum_assignment  # noqa: E402
import sklearn  # noqa: E402
from sklearn.cluster import SpectralClustering  # noqa: E402


def agreement(a, b):
    table = np.zeros((a.max() + 1, b.max() + 1))
    np.add.at(table, (a, b), 1)
    rows, cols = linear_sum_assignment(-table)
    return table[rows, cols].sum() / len(a)


def main():
    folder = sys.argv[1]
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    W = scipy.io.mmread(os.path.join(folder, "gc_affinity.mtx")).tocsr()
    ours = np.loadtxt(os.path.join(folder, "gc_labels_plain.txt"), dtype=int)
    final = np.loadtxt(os.path.join(folder, "gc_labels_final.txt"), dtype=int)
    ours_seconds = float(open(os.path.join(folder, "gc_plain_seconds.txt")).read())
    k = ours.max() + 1
    times, labels = [], None
    for _ in range(reps):
        model = SpectralClustering(n_clusters=k, affinity="precomputed", eigen_solver="arpack",
                                   assign_labels="kmeans", n_init=10, random_state=0)
        t0 = time.perf_counter()
        labels = model.fit_predict(W)
        times.append(time.perf_counter() - t0)
    sk = float(np.median(times))
    print("scikit-learn %s SpectralClustering (arpack, k-means, n_init 10) on %d vertices, %d clusters"
          % (sklearn.__version__, W.shape[0], k))
    print("time: scikit-learn %.0f ms, dresskit %.0f ms (eigen + k-means), ratio %.1f"
          % (sk * 1e3, ours_seconds * 1e3, sk / ours_seconds))
    print("label agreement with dresskit's plain spectral clustering: %.4f" % agreement(labels, ours))
    print("label agreement with dresskit's final segmentation (clean-up, merging): %.4f" % agreement(labels, final))


if __name__ == "__main__":
    main()
