#!/usr/bin/env bash
# Builds nbar's engine in WebAssembly (docs/javascript.md) into build-wasm/ (or $1); with --site
# also the web app as a static site in build-wasm/site/ (docs/web.md: any static web server serves
# it, no nbar process); with --test (which implies --site) runs its tests: the equality test
# against the native program (build/apps/nbar/nbar, which must be built first) and the static
# site in Chromium with every /api request blocked:
#   scripts/build-wasm.sh [build-dir] [--site] [--test]
# It uses Debian's emscripten. yaml-cpp, the one library that must be compiled for WebAssembly,
# comes from Debian's source package (apt-get source, with a deb-src entry added when there is
# none), unpacked and built in the build folder, never in the repository.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-wasm"
run_test=0
site=0
for arg in "$@"; do
  case "$arg" in
    --test) run_test=1 site=1 ;;
    --site) site=1 ;;
    *) build="$(realpath -m "$arg")" ;;
  esac
done
jobs="$(nproc)"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

# Debian's emscripten: its optimiser runs on Debian's node-acorn, found through NODE_PATH.
if ! command -v emcmake >/dev/null 2>&1 || ! command -v dpkg-source >/dev/null 2>&1; then
  $sudo apt-get update
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends emscripten dpkg-dev
fi
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"

# How C++ exceptions are compiled (cmake/wasm.cmake): wasm (the default) or js; yaml-cpp the same way.
exceptions="${NBAR_WASM_EXCEPTIONS:-wasm}"
exceptions_flag=-fwasm-exceptions
if [ "$exceptions" = js ]; then exceptions_flag=-fexceptions; fi

# yaml-cpp for WebAssembly, from the source of the version Debian ships (built once per folder).
deps="$build/deps"
yaml_prefix="$deps/yaml-cpp-$exceptions"
if [ ! -f "$yaml_prefix/lib/libyaml-cpp.a" ]; then
  mkdir -p "$deps/source"
  if ! (cd "$deps/source" && apt-get source --print-uris yaml-cpp >/dev/null 2>&1); then
    echo "adding a deb-src entry for Debian's source packages (/etc/apt/sources.list.d/nbar-deb-src.sources)"
    # The suites and mirror of the machine's own deb entries, for its sources.
    $sudo tee /etc/apt/sources.list.d/nbar-deb-src.sources >/dev/null <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    $sudo apt-get update
  fi
  (cd "$deps/source" && rm -rf yaml-cpp-* && apt-get source yaml-cpp)
  yaml_source="$(find "$deps/source" -maxdepth 1 -type d -name 'yaml-cpp-*' | head -1)"
  emcmake cmake -S "$yaml_source" -B "$deps/yaml-cpp-build-$exceptions" -DCMAKE_BUILD_TYPE=Release \
    -DYAML_CPP_BUILD_TESTS=OFF -DYAML_CPP_BUILD_TOOLS=OFF -DYAML_CPP_BUILD_CONTRIB=OFF -DYAML_BUILD_SHARED_LIBS=OFF \
    -DCMAKE_CXX_FLAGS="$exceptions_flag" -DCMAKE_INSTALL_PREFIX="$yaml_prefix" >/dev/null
  cmake --build "$deps/yaml-cpp-build-$exceptions" -j"$jobs"
  cmake --install "$deps/yaml-cpp-build-$exceptions" >/dev/null
fi

# Ninja when installed (scripts/cmake-options.sh); not ccache, which does not know emscripten.
. "$root/scripts/cmake-options.sh"
generator_options "$build"
emcmake cmake "${generator[@]}" -S "$root" -B "$build" -DNBAR_WASM=ON -DCMAKE_BUILD_TYPE=Release -DNBAR_WASM_YAML_CPP="$yaml_prefix" -DNBAR_WASM_EXCEPTIONS="$exceptions" \
  -DNBAR_NATIVE="$root/build/apps/nbar/nbar" >/dev/null
cmake --build "$build" -j"$jobs" --target nbar_engine
ls -l "$build/web/engine/nbar-engine.wasm"
# The npm package nbar-wasm-<version>.tgz (docs/javascript.md), from the engine just built.
cmake --build "$build" --target nbar_wasm_package
if [ "$site" = 1 ]; then
  # The app's npm packages (esbuild, the editor, the GIF encoder), as the native build installs them.
  ui="$root/web/ui"
  if [ ! -f "$ui/node_modules/.package-lock.json" ] || [ "$ui/package-lock.json" -nt "$ui/node_modules/.package-lock.json" ]; then
    (cd "$ui" && npm ci --no-audit --no-fund --loglevel=error)
  fi
  cmake --build "$build" --target nbar_site
  echo "static site: $build/site ($(du -sh "$build/site" | cut -f1)); serve it with: python3 -m http.server -d $build/site"
fi
if [ "$run_test" = 1 ]; then
  ctest --test-dir "$build" --output-on-failure
fi
