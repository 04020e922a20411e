# deepvox_library(NAME SOURCES... [KERNELS files...] [DEPS libs...]): the static library of one
# folder, linking the folders below it (DEPS). Each file is listed once: SOURCES are the plain
# C++ files, KERNELS the ones that launch parallel_for, compiled by nvcc when CUDA is on
# (deepvox_kernel_sources) and as C++ otherwise; a file that launches without being listed
# under KERNELS fails the CUDA build (cuda/execute.h).
function(deepvox_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;KERNELS;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES} ${ARG_KERNELS})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  if(ARG_KERNELS)
    deepvox_kernel_sources(${ARG_KERNELS})
  endif()
endfunction()
