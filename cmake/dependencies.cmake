include(${CMAKE_CURRENT_LIST_DIR}/optional_dependencies.cmake)
# Every dependency is a Debian package installed by scripts/install-deps.sh; nothing is downloaded.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(tomlplusplus 3 REQUIRED)

# SuiteSparse 5.x on Debian ships no CMake config: find CHOLMOD and its companions by hand.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig REQUIRED)
find_library(AMD_LIBRARY amd REQUIRED)
find_library(COLAMD_LIBRARY colamd REQUIRED)
find_library(CAMD_LIBRARY camd REQUIRED)
find_library(CCOLAMD_LIBRARY ccolamd REQUIRED)
find_library(OPENBLAS_LIBRARY openblas REQUIRED)
add_library(fricon_cholmod INTERFACE)
target_include_directories(fricon_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(fricon_cholmod INTERFACE ${CHOLMOD_LIBRARY} ${AMD_LIBRARY} ${CAMD_LIBRARY}
                      ${COLAMD_LIBRARY} ${CCOLAMD_LIBRARY} ${SUITESPARSE_CONFIG_LIBRARY}
                      ${OPENBLAS_LIBRARY})

# Gmsh 4.x (Debian: libgmsh-dev) ships no CMake config either. It reads and writes the MSH files
# and meshes .geo files through its C API (src/fricon/mesh/gmsh_api.cpp), but is not linked:
# libgmsh brings ~70 more libraries (OpenCASCADE, FLTK, ...) whose loading and initialisation were
# most of the start-up time of every run, so it is opened with dlopen when the first Gmsh file is
# read or written. CMake finds the library only for the name to open, its SONAME (a run that reads
# Gmsh files needs the Debian package of that name, libgmsh4.8; GMSH_SONAME overrides it).
find_path(GMSH_INCLUDE_DIR gmshc.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
if(NOT GMSH_SONAME)
  execute_process(COMMAND ${CMAKE_OBJDUMP} -p ${GMSH_LIBRARY} OUTPUT_VARIABLE _gmsh_dynamic
                  ERROR_QUIET RESULT_VARIABLE _gmsh_objdump)
  if(_gmsh_objdump EQUAL 0 AND _gmsh_dynamic MATCHES "SONAME +([^ \r\n]+)")
    set(_gmsh_soname ${CMAKE_MATCH_1})
  else()  # no objdump or no SONAME: the file the link name points to
    file(REAL_PATH ${GMSH_LIBRARY} _gmsh_file)
    get_filename_component(_gmsh_soname ${_gmsh_file} NAME)
  endif()
  set(GMSH_SONAME ${_gmsh_soname} CACHE STRING "The file name of libgmsh that fricon loads")
endif()
message(STATUS "Gmsh: ${GMSH_SONAME} (${GMSH_LIBRARY}), loaded on first use")
add_library(fricon_gmsh INTERFACE)
target_include_directories(fricon_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_compile_definitions(fricon_gmsh INTERFACE FRICON_GMSH_SONAME="${GMSH_SONAME}")
target_link_libraries(fricon_gmsh INTERFACE ${CMAKE_DL_LIBS})

# muparser (Debian: libmuparser-dev) evaluates the friction law "expression"
# (src/fricon/contact/friction_law.cpp); it ships a pkg-config file only.
find_package(PkgConfig REQUIRED)
pkg_check_modules(MUPARSER REQUIRED IMPORTED_TARGET muparser)

# FCLIB (Debian: libfclib-dev, with HDF5): the problems of other codes (`fricon dual solve`).
# Its config file clears CMAKE_CXX_STANDARD: restore ours.
find_package(fclib 3 REQUIRED CONFIG)
set(CMAKE_CXX_STANDARD 20)

find_package(Threads REQUIRED)
if(FRICON_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(FRICON_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Siconos numerics (Debian: libsiconos-numerics-dev), the peer code that bench/siconos_compare and
# the Siconos verification tests compare with. Optional: without it they are not built.
find_library(SICONOS_NUMERICS siconos_numerics)
find_path(SICONOS_NUMERICS_INCLUDE_DIR fc3d_Solvers.h PATH_SUFFIXES siconos/numerics)
find_path(SICONOS_INCLUDE_DIR SiconosConfig.h PATH_SUFFIXES siconos)
set(SICONOS_NUMERICS_FOUND_ALL FALSE)
if(SICONOS_NUMERICS AND SICONOS_NUMERICS_INCLUDE_DIR AND SICONOS_INCLUDE_DIR)
  set(SICONOS_NUMERICS_FOUND_ALL TRUE)
  message(STATUS "Siconos numerics found (${SICONOS_NUMERICS})")
  add_library(fricon_siconos INTERFACE)
  target_include_directories(fricon_siconos SYSTEM INTERFACE ${SICONOS_NUMERICS_INCLUDE_DIR}
                                                             ${SICONOS_INCLUDE_DIR})
  target_link_libraries(fricon_siconos INTERFACE ${SICONOS_NUMERICS})
endif()
fricon_optional("Siconos numerics" "${SICONOS_NUMERICS_FOUND_ALL}" libsiconos-numerics-dev
                "the comparisons with Siconos (bench, verification)")

# METIS 5 (Debian: libmetis-dev): the partition of the bodies into the subdomains of the Total
# FETI backend ([solver] backend = "tfeti", src/fricon/feti/partition.cpp). Debian ships no CMake
# config for it: found by hand, as the IMPORTED target fricon_metis. Optional: without it fricon
# still builds, gives each body one subdomain, and says how to get METIS when more are asked for.
find_path(METIS_INCLUDE_DIR metis.h)
find_library(METIS_LIBRARY metis)
set(_metis_found FALSE)
if(METIS_INCLUDE_DIR AND METIS_LIBRARY)
  set(_metis_found TRUE)
  message(STATUS "METIS found (${METIS_LIBRARY})")
  add_library(fricon_metis UNKNOWN IMPORTED)
  set_target_properties(fricon_metis PROPERTIES IMPORTED_LOCATION ${METIS_LIBRARY}
                        INTERFACE_INCLUDE_DIRECTORIES ${METIS_INCLUDE_DIR})
endif()
fricon_optional("METIS" "${_metis_found}" libmetis-dev
                "the subdomain partition of backend \"tfeti\" beyond one subdomain per body")

# PETSc 3.18 with MPI (OpenMPI) and MUMPS (Debian: petsc-dev): the distributed backend
# ([solver] backend = "petsc", docs/parallel.md). Optional: without it (or with
# FRICON_WITH_PETSC=OFF) fricon runs on one process and says how to get the backend when asked.
# MUMPS (Debian: libmumps-dev, which petsc-dev brings) is called directly.
if(FRICON_WITH_PETSC)
  find_package(MPI COMPONENTS C CXX)
  pkg_check_modules(PETSC IMPORTED_TARGET PETSc)
  find_library(DMUMPS_LIBRARY dmumps)
  find_library(MUMPS_COMMON_LIBRARY mumps_common)
endif()
if(FRICON_WITH_PETSC AND MPI_FOUND AND PETSC_FOUND AND DMUMPS_LIBRARY AND MUMPS_COMMON_LIBRARY)
  message(STATUS "PETSc ${PETSC_VERSION} with MPI and MUMPS found: the PETSc backend is built")
  add_library(fricon_petsc INTERFACE)
  target_link_libraries(fricon_petsc INTERFACE PkgConfig::PETSC ${DMUMPS_LIBRARY}
                        ${MUMPS_COMMON_LIBRARY} MPI::MPI_CXX MPI::MPI_C)
  find_program(FRICON_MPIEXEC NAMES mpirun mpiexec)
elseif(NOT FRICON_WITH_PETSC)
  message(STATUS "PETSc backend not built (FRICON_WITH_PETSC=OFF)")
endif()
if(FRICON_WITH_PETSC)
  set(_petsc_found FALSE)
  if(TARGET fricon_petsc)
    set(_petsc_found TRUE)
  endif()
  fricon_optional("PETSc with MPI and MUMPS" "${_petsc_found}" petsc-dev
                  "the PETSc backend and its tests")
  if(TARGET fricon_petsc)
    set(_mpiexec_found FALSE)
    if(FRICON_MPIEXEC)
      set(_mpiexec_found TRUE)
    endif()
    fricon_optional("mpirun" "${_mpiexec_found}" "openmpi-bin (petsc-dev brings it)"
                    "the tests under mpirun (label mpi)")
  endif()
endif()
