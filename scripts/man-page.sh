#!/usr/bin/env bash
# Writes the man page nbar(1) from the program's own help: `nbar --help` for the page and one
# section per command from `nbar COMMAND --help`, so the page says what the program says.
# Debian's help2man lays out the page when it is installed (apt-get install help2man); without
# it, the same text goes into a plain page. Run by the build (apps/nbar/CMakeLists.txt):
#   scripts/man-page.sh PATH/TO/nbar OUTPUT.1
set -euo pipefail
program="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
output="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# CLI11 prints its argv[0] in "Usage:": run it as plain `nbar`, found on PATH.
ln -s "$program" "$work/nbar"
export PATH="$work:$PATH"

roff_text() {  # text -> roff, verbatim: backslashes escaped, no line read as a request
  sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"
}
commands="$(nbar --help | awk '/^Subcommands:/{listing = 1; next} listing && /^  [a-z]/{print $1} listing && /^$/{exit}')"
{
  echo "[COMMANDS]"
  echo "Each command has its own options; \\fBnbar\\fR \\fICOMMAND\\fR \\fB--help\\fR prints them, as below."
  for command in $commands; do
    echo ".SS \"nbar $command\""
    echo ".nf"
    # The exit codes and limits, the same for every command, are said once, in the page's top.
    nbar "$command" --help | awk '/^Exit codes:/{exit} {print}' | roff_text
    echo ".fi"
  done
  echo "[SEE ALSO]"
  echo "The manual is in /usr/share/doc/nbar (docs/ of the source): cli.md for every command and"
  echo "option, model-format.md for the model file; the example models are in"
  echo "/usr/share/doc/nbar/examples."
} >"$work/commands.h2m"

if command -v help2man >/dev/null 2>&1; then
  help2man --no-info --no-discard-stderr --section=1 --name="analysis of planar linkages (n-bar mechanisms)" \
    --include="$work/commands.h2m" --output="$output" nbar
  exit 0
fi
version="$(nbar --version | awk '{print $2}')"
{
  echo ".TH NBAR 1 \"\" \"nbar $version\" \"User Commands\""
  echo ".SH NAME"
  echo "nbar \\- analysis of planar linkages (n-bar mechanisms)"
  echo ".SH DESCRIPTION"
  echo ".nf"
  nbar --help | roff_text
  echo ".fi"
  sed -e 's/^\[\(.*\)\]$/.SH \1/' "$work/commands.h2m"
} >"$output"
