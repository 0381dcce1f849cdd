# Sourced by the build scripts: the options each of them gives CMake when it configures a build
# directory, so that they are chosen in one place.
# - ccache, when it is installed: rebuilds are fast; nothing needs it.
# - Ninja, when it is installed and the directory is new: it compiles a library's files while
#   the libraries it links are still being built, where make waits for them (the quick start's
#   build took 3 min 45 s with Ninja against 4 min 28 s with make, on 2 cores). A directory
#   configured before keeps its generator, as CMake refuses to change it.
# Usage: configure_options DIR; then cmake ... "${options[@]}"
#        generator_options DIR; then cmake ... "${generator[@]}" (Ninja alone: scripts/build-wasm.sh)
generator_options() {
  local dir="$1"
  generator=()
  if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
}
configure_options() {
  generator_options "$1"
  options=("${generator[@]}")
  if command -v ccache >/dev/null 2>&1; then options+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
}
