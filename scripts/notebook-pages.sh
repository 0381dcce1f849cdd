#!/usr/bin/env bash
# Runs every notebook top to bottom and writes it as a web page (nbconvert's HTML, figures
# inline), to read the notebooks on a phone or put them on a web site without Jupyter:
#   scripts/notebook-pages.sh [OUT_DIR] [BUILD_DIR]   (defaults: build/notebook-pages, build)
# Needs the Python module built in BUILD_DIR/python and Debian's jupyter-nbconvert.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/build/notebook-pages}"
build="${2:-$root/build}"
mkdir -p "$out"
# The kernel draws figures inline (no MPLBACKEND) and imports the module just built; the
# notebooks find their examples inside it, so they run from any folder.
env -u MPLBACKEND PYTHONPATH="$build/python" PYDEVD_DISABLE_FILE_VALIDATION=1 \
  /usr/bin/python3 -m nbconvert --to html --execute --log-level WARN --output-dir "$out" \
  "$root"/notebooks/*.ipynb
echo "notebook pages in $out"
