#!/usr/bin/env bash
# From nothing to a first result: installs what is missing (only what building and running nbar
# needs: scripts/install-deps.sh), builds nbar, and analyses a bundled four-bar.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
. "$root/scripts/cmake-options.sh"
configure_options "$root/build"
# No tests or benchmarks: their libraries are scripts/test.sh's to install.
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DNBAR_BUILD_TESTS=OFF -DNBAR_BUILD_BENCH=OFF \
  "${options[@]}" >/dev/null
# The program and, when pybind11 was found (scripts/install-deps.sh installs it), the Python
# module, in one build so that the module's files compile beside the program's.
targets=(nbar)
python_module=0
if grep -q '^NBAR_BUILD_PYTHON:BOOL=ON' "$root/build/CMakeCache.txt"; then
  targets+=(nbar_python)
  python_module=1
fi
# One job more than the cores: with Ninja the web bundle's npm ci waits on the network in a pool
# of its own while the compiles keep every core busy (CMakeLists.txt, JOB_POOLS).
cmake --build "$root/build" -j"$(( $(nproc) + 1 ))" --target "${targets[@]}"
nbar="$root/build/apps/nbar/nbar"
model="$root/examples/fourbar-crank-rocker.yaml"
echo
echo "\$ nbar check examples/fourbar-crank-rocker.yaml"
"$nbar" check "$model"
echo
echo "\$ nbar solve examples/fourbar-crank-rocker.yaml --steps 13 --format table --columns 'crank,coupler.*,rocker.*'"
"$nbar" solve "$model" --steps 13 --format table --columns 'crank,coupler.*,rocker.*'
if [ "$python_module" = 1 ]; then
  echo
  echo "\$ PYTHONPATH=build/python /usr/bin/python3 -c 'import nbar; ...'"
  PYTHONPATH="$root/build/python" /usr/bin/python3 -c "
import nbar
r = nbar.load('$model').solve(steps=5, columns='crank,rocker.angle,rocker.omega')
for name in r.columns:
    print(f'{name:>14} [{r.units[name]}]', ' '.join(f'{v:9.3f}' for v in r[name]))
"
fi
