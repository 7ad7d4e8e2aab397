#!/usr/bin/env bash
# Installs PySPH 1.0b2 from PyPI into the virtual environment $1 (compiles with gcc: several
# minutes the first time; nothing to do when it is there). Used by the peer benchmarks beside it.
set -euo pipefail
venv=$1
[ -x "$venv/bin/pysph" ] && exit 0
echo "installing PySPH 1.0b2 into $venv (PyPI; compiles with gcc, several minutes)" >&2
python3 -m venv "$venv"
# Two Cythons: cyarray 1.1 compiles only with Cython 0.29 (Cython 3 refuses its float-to-long
# assignments and its writes to ndarray.data), and PySPH 1.0b2 only with Cython 3 (it reads
# ndarray.data, which only Cython 3 maps to NumPy's accessor).
"$venv/bin/pip" install -q "numpy<2" "cython<3" mako setuptools wheel
"$venv/bin/pip" install -q --no-build-isolation cyarray==1.1 compyle pytools
"$venv/bin/pip" install -q "cython>=3,<3.1"
"$venv/bin/pip" install -q --no-build-isolation pysph==1.0b2
