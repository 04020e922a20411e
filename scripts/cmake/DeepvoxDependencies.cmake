# Third-party libraries, all from Debian packages (scripts/install-deps.sh installs them).
# deepvox_deps carries what every build needs; OpenImageIO (EXR, deep EXR, image metrics) and
# OpenVDB (.vdb volumes, DEEPVOX_OPENVDB) are only found for the full build, so the lean GPU-node
# binary needs nothing beyond glibc, libstdc++ and the NVIDIA driver.
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Threads REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb REQUIRED)
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
# CGAL is header-only; its exact-number fallback uses Boost.Multiprecision instead of GMP so no
# binary depends on libgmp.
set(CGAL_DISABLE_GMP ON)
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL CONFIG REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
include(CGAL_Eigen3_support)  # CGAL::Eigen3_support: hole fairing and parameterization

add_library(deepvox_deps INTERFACE)
# tinygltf is compiled from its header in render/load/gltf_impl.cpp (no libtinygltf.so at run time).
target_include_directories(deepvox_deps SYSTEM INTERFACE ${STB_INCLUDE_DIR} ${TINYGLTF_INCLUDE_DIR})
target_link_libraries(deepvox_deps INTERFACE glm::glm nlohmann_json::nlohmann_json CLI11::CLI11
                                             Threads::Threads CGAL::CGAL CGAL::Eigen3_support)

if(NOT DEEPVOX_LEAN)
  find_package(OpenImageIO CONFIG REQUIRED)
  # Debian 12's OpenImageIO target names /usr/include/opencv4 as an include directory although
  # deepvox needs no OpenCV; drop include directories that do not exist so CMake accepts it.
  get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
  set(_oiio_existing)
  foreach(_dir IN LISTS _oiio_includes)
    if(EXISTS "${_dir}" OR _dir MATCHES "^\\$<")
      list(APPEND _oiio_existing "${_dir}")
    endif()
  endforeach()
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_existing}")
endif()
if(DEEPVOX_OPENVDB AND NOT DEEPVOX_LEAN)
  # An imported target of our own: Debian 12's FindOpenVDB.cmake also asks for Boost.Iostreams
  # (not a dependency of libopenvdb-dev), which nothing here uses. OpenVDB's headers need TBB's
  # and Imath's (its half type), both dependencies of libopenvdb-dev.
  find_path(OPENVDB_INCLUDE_DIR openvdb/openvdb.h)
  find_library(OPENVDB_LIBRARY openvdb)
  find_package(TBB CONFIG)
  find_package(Imath CONFIG)
  if(NOT OPENVDB_INCLUDE_DIR OR NOT OPENVDB_LIBRARY OR NOT TARGET TBB::tbb OR NOT TARGET Imath::Imath)
    message(FATAL_ERROR "OpenVDB not found: run scripts/install-deps.sh (libopenvdb-dev), or "
                        "configure with -DDEEPVOX_OPENVDB=OFF to build without .vdb volumes")
  endif()
  add_library(OpenVDB::openvdb UNKNOWN IMPORTED)
  set_target_properties(OpenVDB::openvdb PROPERTIES IMPORTED_LOCATION "${OPENVDB_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${OPENVDB_INCLUDE_DIR}"
                        INTERFACE_LINK_LIBRARIES "TBB::tbb;Imath::Imath")
endif()
if(DEEPVOX_TESTS)
  find_package(GTest REQUIRED)
endif()
if(DEEPVOX_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
