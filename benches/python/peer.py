"""What the Python benchmarks run against, recorded and at its normal speed.

Some machines set `OPENBLAS_CORETYPE` and `OPENBLAS_L2_SIZE`, which make numpy and scipy slower
than they are elsewhere: a ratio measured against a slowed peer flatters us. OpenBLAS reads
them when it loads, so `normal_speed()` re-runs the script without them before numpy is
imported (inbetween uses no BLAS; both sides then run as on a machine without them), and
`describe()` prints the versions and the BLAS build with the figures.
"""

import os
import platform
import sys

VARIABLES = ("OPENBLAS_CORETYPE", "OPENBLAS_L2_SIZE")


def normal_speed():
    """Re-executes this script without the OpenBLAS variables, if any is set. Call it before
    importing numpy."""
    if any(v in os.environ for v in VARIABLES):
        env = {k: v for k, v in os.environ.items() if k not in VARIABLES}
        os.execve(sys.executable, [sys.executable, *sys.argv], env)


def describe():
    """One line: Python, numpy, scipy (when installed), the BLAS numpy was built with, and the
    OpenBLAS variables (unset after `normal_speed`)."""
    import numpy as np

    parts = [f"Python {platform.python_version()}", f"numpy {np.__version__}"]
    try:
        import scipy

        parts.append(f"scipy {scipy.__version__}")
    except ImportError:
        pass
    try:
        blas = np.show_config(mode="dicts")["Build Dependencies"]["blas"]
        parts.append(f"BLAS {blas.get('name')} {blas.get('version')}")
    except Exception:  # numpy < 1.26 has no dict mode
        parts.append("BLAS unknown")
    unset = ", ".join(f"{v}={os.environ[v]}" for v in VARIABLES if v in os.environ) or "none"
    parts.append(f"OpenBLAS variables set: {unset}")
    parts.append(f"{os.cpu_count()} cores")
    return "; ".join(parts)
