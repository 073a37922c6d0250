# A fuzzing build (MOTIF_BUILD_FUZZERS, tests/fuzz) needs clang: libFuzzer ships with it.
if(MOTIF_BUILD_FUZZERS AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "MOTIF_BUILD_FUZZERS needs clang and its libFuzzer runtime "
                      "(Debian: clang libclang-rt-14-dev); configure a separate build directory "
                      "with CC=clang CXX=clang++")
endif()

# motif_set_warnings(target): the project's standard and warning flags, set per target.
function(motif_set_warnings target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  if(MOTIF_BUILD_FUZZERS)
    # Coverage feedback for libFuzzer in every library, and ASan/UBSan with UB fatal, so that
    # any memory error or undefined behaviour a fuzzer reaches is reported as a crash. The
    # fuzzer executables add -fsanitize=fuzzer at link time (tests/fuzz/CMakeLists.txt).
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# motif_add_library(name SOURCES...): a static library motif_<name> with alias motif::<name>.
function(motif_add_library name)
  add_library(motif_${name} STATIC ${ARGN})
  add_library(motif::${name} ALIAS motif_${name})
  # The public headers too: the engine's options start from include/motifmine/defaults.h.
  target_include_directories(motif_${name} PUBLIC ${PROJECT_SOURCE_DIR}
                                                  ${PROJECT_SOURCE_DIR}/include)
  motif_set_warnings(motif_${name})
endfunction()
