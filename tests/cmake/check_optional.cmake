# cmake -DFRICON_REQUIRE_OPTIONAL=ON|OFF -DFOUND=TRUE|FALSE -P check_optional.cmake: calls
# fricon_optional as dependencies.cmake does, for a dependency that was (not) found.
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/optional_dependencies.cmake)
fricon_optional("a test dependency" "${FOUND}" test-package "the tests of a test group")
