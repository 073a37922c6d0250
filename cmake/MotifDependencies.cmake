# Resolves every third-party dependency once, as imported targets with stable names.
# All of them come from Debian packages (see scripts/install_deps.sh).
find_package(Threads REQUIRED)
find_package(Boost 1.74 REQUIRED COMPONENTS iostreams program_options)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)

# zstd ships no CMake config on Debian 12: resolve it through pkg-config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
add_library(motif::zstd ALIAS PkgConfig::ZSTD)
# xxHash (XXH3 block checksums): header + library from libxxhash-dev.
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)
add_library(motif::xxhash ALIAS PkgConfig::XXHASH)
