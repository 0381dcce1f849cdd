#!/usr/bin/env bash
# Makes nbar's packages into dist/ (docs/install.md):
#   dist/nbar-<version>-cp311-cp311-linux_x86_64.whl   the Python module (pip install)
#   dist/nbar_<version>_amd64.deb                      the program, the module, the manual
#   dist/libnbar-dev_<version>_amd64.deb               the C++ library and its CMake package
#   dist/web/                                          the static web app, when a browser build exists
#   dist/nbar-wasm-<version>.tgz                       the engine for JavaScript (npm), when build-wasm/ has it
# It builds in the tree's build directory (NBAR_BUILD_DIR, default build/; configured here,
# without tests and benchmarks, when it is not yet), so after scripts/quickstart.sh or
# scripts/test.sh little is left to build. What it needs beyond the quick start's packages
# (setuptools, wheel, pip, help2man, dpkg-dev): scripts/install-deps.sh --tests.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${NBAR_BUILD_DIR:-$root/build}"
dist="$root/dist"
python=/usr/bin/python3  # Debian's: the wheel and the .deb are for its Python 3.11

if [ ! -f "$build/CMakeCache.txt" ]; then
  . "$root/scripts/cmake-options.sh"
  configure_options "$build"
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DNBAR_BUILD_TESTS=OFF -DNBAR_BUILD_BENCH=OFF \
    "${options[@]}" >/dev/null
fi
if ! grep -q '^NBAR_BUILD_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "package.sh: $build does not build the Python module (apt-get install pybind11-dev python3-dev)" >&2
  exit 1
fi
rm -rf "$dist"
mkdir -p "$dist"

echo "== the wheel"
# Built in the same build directory: the module is built (or found up to date) there.
NBAR_CMAKE_BUILD_DIR="$build" "$python" -m pip wheel --no-build-isolation --no-deps --no-index -q -w "$dist" "$root"
rm -rf "$root/build-wheel/setuptools"  # setuptools' staging

echo "== the .deb packages"
cmake --build "$build" -j"$(nproc)"
(cd "$build" && cpack -G DEB -B "$build/packages" >/dev/null)
cp "$build"/packages/*.deb "$dist/"

# The static web app (the browser build of web/ui): copied when a build of it exists.
web_static="${NBAR_WEB_STATIC_DIR:-$build/web/static}"
if [ -f "$web_static/index.html" ]; then
  echo "== the static web app"
  cp -r "$web_static" "$dist/web"
fi
# The engine's npm package (docs/javascript.md): copied when a WebAssembly build made it.
wasm_tarball="$(ls "${NBAR_WASM_BUILD_DIR:-$root/build-wasm}"/nbar-wasm-*.tgz 2>/dev/null | head -1 || true)"
if [ -n "$wasm_tarball" ]; then
  echo "== the npm package"
  cp "$wasm_tarball" "$dist/"
fi
ls -l "$dist"
