# CUDA detection: DEEPVOX_CUDA=AUTO builds the CUDA backend when a CUDA compiler is found,
# ON requires one, OFF skips it. Sets DEEPVOX_WITH_CUDA and the helper
# deepvox_kernel_sources(): files of shared host/device code that nvcc compiles when CUDA is on
# (so the same parallel_for lambdas become kernels) and g++ compiles otherwise.
include(CheckLanguage)
set(DEEPVOX_WITH_CUDA OFF)
if(NOT DEEPVOX_CUDA STREQUAL "OFF")
  if(NOT DEFINED CMAKE_CUDA_COMPILER AND EXISTS /usr/local/cuda/bin/nvcc)
    set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc)
  endif()
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
      # sm_90 machine code plus PTX for newer GPUs.
      set(CMAKE_CUDA_ARCHITECTURES "90-real;90-virtual")
    endif()
    enable_language(CUDA)
    # CMake 3.25 does not know nvcc 13's C++20 dialect flag: tell it.
    set(CMAKE_CUDA20_STANDARD_COMPILE_OPTION "-std=c++20")
    set(CMAKE_CUDA20_EXTENSION_COMPILE_OPTION "-std=c++20")
    set(CMAKE_CUDA_STANDARD 20)
    set(CMAKE_CUDA_STANDARD_REQUIRED ON)
    set(CMAKE_CUDA_RUNTIME_LIBRARY Static)
    find_package(CUDAToolkit REQUIRED)
    set(CMAKE_CUDA_FLAGS
        "${CMAKE_CUDA_FLAGS} --extended-lambda --expt-relaxed-constexpr -diag-suppress 20012,20014")
    set(DEEPVOX_WITH_CUDA ON)
  elseif(DEEPVOX_CUDA STREQUAL "ON")
    message(FATAL_ERROR "DEEPVOX_CUDA=ON but no CUDA compiler was found")
  endif()
endif()
message(STATUS "deepvox: CUDA backend ${DEEPVOX_WITH_CUDA}")

function(deepvox_kernel_sources)
  if(DEEPVOX_WITH_CUDA)
    set_source_files_properties(${ARGN} DIRECTORY ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}
                                PROPERTIES LANGUAGE CUDA)
  endif()
endfunction()
