# Sourced by the build scripts. generator_args DIR: the CMake generator for a new build
# directory: Ninja when it is installed (a Release build of everything took 293 s of wall time
# with Ninja and 316 s with Make on the same idle machine, docs/reliability.md, "Build and test
# time"), else CMake's default. A directory configured before keeps its generator.
generator_args() {
  if [ ! -f "$1/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then
    echo "-G Ninja"
  fi
}
