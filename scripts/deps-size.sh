#!/usr/bin/env bash
# Measures what scripts/install-deps.sh installs on a bare Debian bookworm, without one: apt
# solves the install against a made-up dpkg status that holds only a bare system, and the
# Installed-Size and Size (download) of every package it would install are added up.
# The bare system is what debootstrap's minbase makes: every package of Priority required or
# Essential, with what they depend on, and apt (88 packages; a minbase chroot had the same 88). Its entries are
# copied from this machine's dpkg status, so every one of them must be installed here (it is, on
# any Debian). Prints one line per set: packages, download and installed size.
#   scripts/deps-size.sh            the quick start's set and the tests' set (install-deps.sh --tests)
#   scripts/deps-size.sh PKG...     any list of packages
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

simulate() {  # status file, packages... -> "name version" of each package apt would install
  local status="$1"
  shift
  apt-get -s -o Dir::State::status="$status" -o APT::Install-Recommends=false install "$@" 2>&1 |
    awk '/^Inst /{gsub(/[()]/, "", $3); print $2, $3}'
}

# The bare system: the required and essential packages and what they depend on, solved against
# an empty status. usr-is-merged is named because bookworm's images have it (apt would otherwise
# take the first alternative of init-system-helpers' dependency, usrmerge).
: >"$work/empty"
apt-cache dumpavail |
  awk -v RS= '/(^|\n)Priority: required/ || /(^|\n)Essential: yes/ {
    match($0, /^Package: [^\n]+/); print substr($0, 10, RLENGTH - 9) }' | sort -u >"$work/required"
simulate "$work/empty" $(cat "$work/required") usr-is-merged apt | awk '{print $1}' >"$work/bare"
while read -r package; do
  dpkg-query -s "$package" 2>/dev/null || { echo "not installed here: $package (needed to stand for a bare system)" >&2; exit 1; }
  echo
done <"$work/bare" >"$work/status"

measure() {  # label, packages... -> one line of sums
  local label="$1"
  shift
  simulate "$work/status" "$@" >"$work/plan"
  local count
  count="$(wc -l <"$work/plan")"
  # apt-cache show prints each version's stanza; Installed-Size is in KiB, Size in bytes.
  apt-cache show $(awk '{print $1 "=" $2}' "$work/plan") 2>/dev/null |
    awk -v label="$label" -v count="$count" -v bare="$(wc -l <"$work/bare")" '
      /^Package: /{ first = !($2 in counted); counted[$2] = 1 }  # a version in two suites is shown twice
      /^Installed-Size: /{ if (first) installed += $2 }
      /^Size: /{ if (first) download += $2 }
      END { printf "%s: %d packages over a bare bookworm of %d, download %.0f MB, installed %.0f MB\n",
                   label, count, bare, download / 1e6, installed * 1024 / 1e6 }'
}

if [ $# -gt 0 ]; then
  measure "given" "$@"
else
  measure "quick start (install-deps.sh)" $("$root/scripts/install-deps.sh" --list)
  measure "tests too (install-deps.sh --tests)" $("$root/scripts/install-deps.sh" --list --tests)
fi
