#!/usr/bin/env bash
# Installs the Debian packages nbar needs, when any is missing.
#   scripts/install-deps.sh           what building and running nbar needs (scripts/quickstart.sh)
#   scripts/install-deps.sh --tests   that and what the tests, benchmarks, fuzzing and packaging
#                                     need (scripts/test.sh)
#   scripts/install-deps.sh --list [--tests]   prints the package names and installs nothing
#                                     (scripts/deps-size.sh measures them)
# The sizes of both sets, from a bare bookworm: docs/install.md.
set -euo pipefail
build_packages=(
  build-essential cmake pkg-config
  ninja-build  # builds faster than make (scripts/cmake-options.sh); make still works
  libeigen3-dev libyaml-cpp-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libcairo2-dev libcgif-dev
  libcpp-httplib-dev  # nbar serve: the web server
  # The Python module, for Debian's /usr/bin/python3
  pybind11-dev python3-dev python3-numpy
  # The web app is bundled by npm packages (web/ui) during the build
  nodejs npm
)
test_packages=(
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev
  ffmpeg  # nbar animate -o x.mp4 and the MP4 of nbar serve (optional at run time; tests check videos with ffprobe)
  nginx  # tests: docs/deploy.md's two nbar serve instances behind nginx (Web.Nginx)
  libtinyxml2-dev chromium  # tests: SVG parsed as XML; the HTML animation run in headless Chromium
  phcpack  # tests and bench/: the five-point synthesis cross-checked and timed against PHCpack
  calculix-ccx  # tests: the plane-stress finite elements cross-checked against CalculiX (ccx, run as a program)
  clang libclang-rt-14-dev  # scripts/fuzz.sh: the libFuzzer harnesses (clang++ -fsanitize=fuzzer)
  # The Python module's tests: pytest, plots (optional at run time), the notebooks run by nbclient
  # on an ipykernel, sympy's derivatives as a reference, docs/python.md's Result.to_pandas()
  python3-matplotlib python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-sympy
  python3-pandas
  python3-nbconvert  # the notebooks as web pages read at 390 px (scripts/notebook-pages.sh)
  python3-mpmath python3-yaml  # tests: the 60-digit reference of six-bars near a limit (tests/kinematics/near_limit_reference.py)
  python3-mypy  # the Python stubs: stubtest against the module, mypy --strict on the docs' examples
  # scripts/package.sh and its test: the wheel (setuptools, wheel, pip, venv), the man page
  # (help2man), the .deb's dependencies (dpkg-shlibdeps, in dpkg-dev)
  python3-setuptools python3-wheel python3-pip python3-venv help2man dpkg-dev
  emscripten  # scripts/build-wasm.sh: the engine in WebAssembly (dpkg-dev, above, unpacks yaml-cpp's source package)
)

list_only=0
with_tests=0
for argument in "$@"; do
  case "$argument" in
    --list) list_only=1 ;;
    --tests) with_tests=1 ;;
    *) echo "usage: $0 [--tests] [--list]" >&2; exit 2 ;;
  esac
done
packages=("${build_packages[@]}")
if [ "$with_tests" = 1 ]; then packages+=("${test_packages[@]}"); fi
if [ "$list_only" = 1 ]; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

# A Node installed otherwise (not from Debian) bundles the web app as well.
have_node=0
if command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then have_node=1; fi
missing=()
for p in "${packages[@]}"; do
  if [ "$have_node" = 1 ] && { [ "$p" = nodejs ] || [ "$p" = npm ]; }; then continue; fi
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "installing: ${missing[*]}"
$sudo apt-get update
# dpkg's --force-unsafe-io skips the sync after each file it unpacks, as Debian's container images
# do: the quick start's 544 packages took 3 min 58 s to install on a bare bookworm with it off.
# A power cut in the middle could leave a half-written package, which apt-get reinstalls.
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
  -o Dpkg::Options::=--force-unsafe-io "${missing[@]}"
