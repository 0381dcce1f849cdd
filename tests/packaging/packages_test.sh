#!/usr/bin/env bash
# Installs what scripts/package.sh made, as a user would, into a scratch folder, and uses it:
# - the wheel into a fresh venv (with Debian's numpy through --system-site-packages): pip show,
#   the version against CMake's, the README's Python example, pip uninstall; and into a venv
#   without numpy, where `import nbar` must say what to install; a wheel built without pybind11
#   must fail at its build, naming the package;
# - the .deb packages unpacked into a scratch root (dpkg -x: no root, no change to this machine):
#   their declared dependencies, `nbar check` on a bundled example, the man page, the bash
#   completion, the Python module for Debian's python3, and examples/cpp/analyse-model built
#   with find_package(nbar) from that root.
#   tests/packaging/packages_test.sh [DIST]      (default: dist/ of this tree)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dist="$(cd "${1:-$root/dist}" && pwd)"
python=/usr/bin/python3
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
failures=0
passes=0
pass() { passes=$((passes + 1)); echo "ok: $*"; }
fail() { failures=$((failures + 1)); echo "FAILED: $*"; }
expect() {  # description, command...: passes when the command succeeds
  local description="$1"
  shift
  if "$@" >"$scratch/last.log" 2>&1; then pass "$description"; else fail "$description"; cat "$scratch/last.log"; fi
}

version="$(sed -n 's/^project(nbar VERSION \([0-9.]*\).*/\1/p' "$root/CMakeLists.txt")"
wheels=("$dist"/nbar-"$version"-cp311-cp311-linux_x86_64.whl)
debs=("$dist/nbar_${version}_amd64.deb" "$dist/libnbar-dev_${version}_amd64.deb")
for file in "${wheels[@]}" "${debs[@]}"; do
  [ -f "$file" ] || { echo "FAILED: no $file (run scripts/package.sh)"; exit 1; }
done

echo "== the wheel, in a fresh venv with Debian's numpy"
venv="$scratch/venv"
"$python" -m venv --system-site-packages "$venv"
expect "pip install the wheel, offline" "$venv/bin/python" -m pip install --no-index -q "${wheels[0]}"
expect "pip show nbar gives version $version" \
  bash -c "'$venv/bin/python' -m pip show nbar | grep -qx 'Version: $version'"
# The README's Python example, as written, from a folder that has the example model it loads.
mkdir -p "$scratch/work/examples"
cp "$root/examples/fourbar-crank-rocker.yaml" "$scratch/work/examples/"
awk '/^## Python and Jupyter/{section = 1} section && /^```python/{code = 1; next} code && /^```/{exit} code' \
  "$root/README.md" >"$scratch/work/readme_example.py"
cat >>"$scratch/work/readme_example.py" <<EOF

# What the example made, checked: the installed package, its version, the sweep's numbers.
import importlib.metadata, pathlib
assert pathlib.Path(nbar.__file__).is_relative_to("$venv"), nbar.__file__
assert nbar.__version__ == importlib.metadata.version("nbar") == "$version", nbar.__version__
assert len(r["rocker.omega"]) == 361
# The crank-rocker's rocker swings between 85.124 and 151.045 deg (README, nbar check).
assert abs(min(r["rocker.angle"]) - 85.124) < 0.01 and abs(max(r["rocker.angle"]) - 151.045) < 0.01
print("readme example:", nbar.__version__, len(r["rocker.omega"]), "samples")
EOF
expect "the README's Python example runs on the installed wheel" \
  bash -c "cd '$scratch/work' && MPLBACKEND=Agg '$venv/bin/python' readme_example.py"
expect "pip uninstall nbar" "$venv/bin/python" -m pip uninstall -y -q nbar

echo "== the wheel, in a venv without numpy"
bare_venv="$scratch/bare-venv"
"$python" -m venv "$bare_venv"
expect "pip install the wheel without its dependency" \
  "$bare_venv/bin/python" -m pip install --no-index --no-deps -q "${wheels[0]}"
"$bare_venv/bin/python" -c "import nbar" >"$scratch/no-numpy.log" 2>&1 && fail "import nbar without numpy succeeded"
if grep -q "ImportError: nbar needs numpy: apt-get install python3-numpy" "$scratch/no-numpy.log"; then
  pass "import nbar without numpy says what to install"
else
  fail "import nbar without numpy"
  cat "$scratch/no-numpy.log"
fi

echo "== a wheel built without pybind11"
# CMake is told to find no pybind11, in a build directory of its own: the build must stop at
# its configure step, naming the Debian package.
NBAR_CMAKE_BUILD_DIR="$scratch/no-pybind11" NBAR_CMAKE_ARGS=-DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON \
  "$python" -m pip wheel --no-build-isolation --no-deps --no-index -q -w "$scratch/no-pybind11-dist" "$root" \
  >"$scratch/no-pybind11.log" 2>&1 && fail "a wheel was built without pybind11"
if grep -q "nbar's Python module needs pybind11: apt-get install pybind11-dev" "$scratch/no-pybind11.log" &&
  ! ls "$scratch"/no-pybind11-dist/*.whl >/dev/null 2>&1; then
  pass "the wheel's build without pybind11 fails, naming pybind11-dev"
else
  fail "the wheel's build without pybind11"
  cat "$scratch/no-pybind11.log"
fi

echo "== the .deb packages, unpacked into a scratch root"
prefix="$scratch/root"
for deb in "${debs[@]}"; do dpkg-deb -x "$deb" "$prefix"; done
depends="$(dpkg-deb -f "${debs[0]}" Depends)"
echo "nbar depends on: $depends"
for needed in libyaml-cpp0.7 libfmt9 libcairo2 libcgif0 libcpp-httplib0.11 python3-numpy; do
  expect "nbar's .deb depends on $needed" grep -q "$needed" <<<"$depends"
done
expect "nbar's .deb depends on no -dev package" bash -c "! grep -q -- '-dev' <<<'$depends'"
model="$prefix/usr/share/doc/nbar/examples/fourbar-crank-rocker.yaml"
expect "nbar check on the packaged example" \
  bash -c "'$prefix/usr/bin/nbar' check '$model' | grep -q 'the rocker rocker swings 65.921 deg'"
expect "the man page has every command" \
  bash -c "grep -q '^\\.SS \"nbar check\"' '$prefix/usr/share/man/man1/nbar.1' && grep -q '^\\.SS \"nbar serve\"' '$prefix/usr/share/man/man1/nbar.1'"
completion="$prefix/usr/share/bash-completion/completions/nbar"
expect "bash completes nbar's commands and options" bash -c "
  source '$completion'
  COMP_WORDS=('$prefix/usr/bin/nbar' ch); COMP_CWORD=1; _nbar; [ \"\${COMPREPLY[*]}\" = check ] || exit 1
  COMP_WORDS=('$prefix/usr/bin/nbar' solve --ste); COMP_CWORD=2; _nbar; [ \"\${COMPREPLY[*]}\" = --steps ]"
module_dir="$(cd "$prefix"/usr/lib/python3*/dist-packages && pwd)"
expect "the .deb's Python module imports with Debian's python3" bash -c "
  cd '$scratch' && PYTHONPATH='$module_dir' '$python' -c \"import nbar, sys; assert nbar.__file__.startswith('$module_dir'); assert nbar.__version__ == '$version'; print(nbar.load('$model').solve(steps=5).rows)\""
expect "find_package(nbar) from the root builds examples/cpp/analyse-model" bash -c "
  cmake -S '$prefix/usr/share/doc/nbar/examples/cpp/analyse-model' -B '$scratch/cpp' -DCMAKE_PREFIX_PATH='$prefix/usr' \
        -DCMAKE_BUILD_TYPE=Release >/dev/null && cmake --build '$scratch/cpp' >/dev/null"
expect "the program built against the package gives a torque" \
  bash -c "'$scratch/cpp/analyse-model' '$prefix/usr/share/doc/nbar/examples/fourbar-steel-bars.yaml' | grep -Eq 'crank = +[0-9.]+ deg: +-?[0-9]+\\.[0-9]+ N m'"

echo "packages: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
