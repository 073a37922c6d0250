# motif_set_warnings(target): the project's standard and warning flags, set per target.
function(motif_set_warnings target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  if(MOTIF_ENABLE_SANITIZERS)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# motif_add_library(name SOURCES...): a static library motif_<name> with alias motif::<name>.
function(motif_add_library name)
  add_library(motif_${name} STATIC ${ARGN})
  add_library(motif::${name} ALIAS motif_${name})
  target_include_directories(motif_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  motif_set_warnings(motif_${name})
endfunction()
