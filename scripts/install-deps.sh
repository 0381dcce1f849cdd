#!/usr/bin/env bash
# Installs the Debian packages nbar needs to build and test, when any is missing.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libyaml-cpp-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev
  libcairo2-dev libcgif-dev
  libcpp-httplib-dev  # nbar serve: the web server
  ffmpeg  # nbar animate -o x.mp4 and the MP4 of nbar serve (run as a program; tests check its videos with ffprobe)
  nginx  # tests: docs/deploy.md's two nbar serve instances behind nginx (Web.Nginx)
  libtinyxml2-dev chromium  # tests: SVG parsed as XML; the HTML animation run in headless Chromium
  phcpack  # tests and bench/: the five-point synthesis cross-checked and timed against PHCpack
  calculix-ccx  # tests: the plane-stress finite elements cross-checked against CalculiX (ccx, run as a program)
  clang libclang-rt-14-dev  # scripts/fuzz.sh: the libFuzzer harnesses (clang++ -fsanitize=fuzzer)
  # The Python module, for Debian's /usr/bin/python3, and its tests: pytest, the notebooks run
  # by nbclient on an ipykernel, sympy's derivatives as a reference
  pybind11-dev python3-dev python3-numpy python3-matplotlib
  python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-sympy
  python3-pandas  # docs/python.md's example of Result.to_pandas(), run by the tests
)
# The web app is bundled by npm packages (web/ui) during the build: Node and npm, unless a Node
# is already installed (from Debian or elsewhere).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "installing: ${missing[*]}"
$sudo apt-get update
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
