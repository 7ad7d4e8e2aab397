#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The documentation site (MkDocs Material, mkdocs.yml): docs/ staged in build/site-src with the
# notebooks run from top to bottom in a scratch folder (so their figures are in the pages and nothing
# they write lands in docs/), then `mkdocs build --strict`, which fails on a broken link or a
# reference the API pages cannot resolve. Needs the build (scripts/build.sh) and the virtual
# environment of scripts/setup-python.sh. Usage: bash scripts/docs-site.sh; then open
# build/site/index.html.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
py="$root/.venv/bin/python"
if ! "$py" -c "import mkdocs, mkdocs_jupyter, mkdocstrings, nbclient" 2>/dev/null; then
  echo "docs-site: skipped: MkDocs is not installed in .venv (bash scripts/setup-python.sh)"
  exit 77
fi
stage="$root/build/site-src"
rm -rf "$stage"
mkdir -p "$stage"
cp -r docs/. "$stage/"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
# The kernel sees the package and the CLI just built, and the project's data, as the notebooks'
# test gives them; Jupyter's own (inline) plotting backend.
PATH="$root/build:$PATH" PYTHONPATH="$root/build/python" RUNNEL_SOURCE_DIR="$root" \
  env -u MPLBACKEND "$py" - "$scratch" "$stage"/notebooks/*.ipynb <<'PY'
import sys
import nbclient
import nbformat
scratch = sys.argv[1]
for path in sys.argv[2:]:
    notebook = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": scratch}}).execute()
    nbformat.write(notebook, path)
    print(f"docs-site: ran {path.rsplit('/', 1)[-1]}")
PY
# From build/, where mkdocs-jupyter keeps its .cache.
(cd "$root/build" && NO_MKDOCS_2_WARNING=1 PYTHONPATH="$root/build/python" "$root/.venv/bin/mkdocs" build \
  --strict --quiet -f "$root/mkdocs.yml")
echo "docs-site: build/site/index.html"
