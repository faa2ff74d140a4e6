# Optional dependencies and what they switch on (Siconos: the peer comparisons; PETSc with MPI
# and MUMPS: the distributed backend and its tests; pytest: the Python module's tests).
#
# A missing optional dependency only drops its part of the build, with a status line. That is
# right on a user's machine, but in CI it would lose a group of tests silently: the install step
# installed the package, so CMake not finding it is a defect. With FRICON_REQUIRE_OPTIONAL=ON
# (`make` sets it when CI=true) each one that is asked for and missing is a configure error.
option(FRICON_REQUIRE_OPTIONAL
       "Fail the configuration when an optional dependency is missing (CI: the install step installed them all)"
       OFF)

# fricon_optional(NAME FOUND PACKAGE WHAT): FOUND is the result of looking for NAME; PACKAGE is
# the Debian package that brings it; WHAT is what is not built without it.
function(fricon_optional name found package what)
  if(found)
    return()
  endif()
  if(FRICON_REQUIRE_OPTIONAL)
    message(FATAL_ERROR "${name} not found, so ${what} would not be built, but "
                        "FRICON_REQUIRE_OPTIONAL is ON (CI): install ${package} "
                        "(scripts/install-deps.sh lists it) or see why CMake does not find it")
  endif()
  message(STATUS "${name} not found (${package}): ${what} not built")
endfunction()
