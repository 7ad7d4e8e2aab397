#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's test command: installs what is missing (the Python package too), builds, checks
# formatting, runs every test (the pytest suite of the Python package among them),
# then the suite again under ASan + UBSan with each reader's fuzz target (scripts/sanitize.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/setup-python.sh  # .venv with the runnel package installed by pip (tested below)
bash scripts/build.sh
bash scripts/check-format.sh
(cd build && ctest -j "$(nproc)" --output-on-failure)
bash scripts/sanitize.sh
