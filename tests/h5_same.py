"""h5_same.py A.h5 B.h5 - exit 0 when the two HDF5 files hold the same datasets with the same bits (attributes, the
runs' provenance among them, aside); else name what differs. Used by tests/mpi_run_check.sh to hold a run split over
MPI ranks to the one-process run."""
import sys

import h5py
import numpy as np


def datasets(f):
    names = []
    f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
    return names


def main():
    a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
    na, nb = datasets(a), datasets(b)
    bad = sorted(set(na) ^ set(nb))
    for n in bad:
        print("only in one file:", n)
    for n in sorted(set(na) & set(nb)):
        x, y = a[n][()], b[n][()]
        if isinstance(x, bytes) or isinstance(y, bytes):
            same = x == y
        else:
            x, y = np.asarray(x), np.asarray(y)
            same = x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes()
        if not same:
            print("differs:", n)
            bad.append(n)
    print(("same: " if not bad else "DIFFERENT: ") + "%d datasets" % len(na))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
