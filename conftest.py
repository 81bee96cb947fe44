"""Settings of every test process (the doctests of ``dispersion/`` and ``tests/``).

One BLAS thread per process: the tests run one process per CPU (pyproject's addopts, ``-n
auto``), and OpenBLAS's own threads on top of them fight over the same cores, spinning while
they wait (the default run: about 8 % more CPU seconds with them; a 400 x 400 ``eigvalsh``
took 4 to 14 times the CPU). Their matrices are small: one thread is also the faster for a
single process. Set here, before numpy is first imported; a variable the caller set wins.
"""
from __future__ import annotations

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")
