#!/usr/bin/env bash
# Installs the Debian packages nbar needs to build and test, when any is missing.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libyaml-cpp-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev
  libcairo2-dev libcgif-dev
  libtinyxml2-dev chromium  # tests: SVG parsed as XML; the HTML animation run in headless Chromium
  phcpack  # tests and bench/: the five-point synthesis cross-checked and timed against PHCpack
)
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
