#pragma once
// parallel/mpi: a fault injected on purpose, for the tests only (docs/parallel.md, "When a rank
// fails"). FRICON_TEST_FAULT=<phase>:<rank>:<kind> in the environment makes test_fault(phase)
// throw on that rank, the first time the run reaches the phase, so that the tests can check
// that a failure of one rank in any phase of a distributed run ends every rank. Without the
// variable test_fault() costs a comparison; it is compiled in always, so that the program the
// tests run is the one users run.

#include <string_view>

namespace fricon::parallel {

/// The phases of a distributed run that test_fault() is called in, in the order a run reaches
/// them (docs/parallel.md lists what each covers); "subdomains" and "products" are backend
/// tfeti's (parallel/mpi/feti_ranks.hpp): a rank factoring its own subdomains, and the sum of a
/// product with F.
inline constexpr std::string_view kFaultPhases[] = {
    "model", "share", "partition", "scatter", "assembly", "analysis",   "factorize",
    "schur", "setup", "outer",     "solve",   "gather",   "subdomains", "products",
};

/// Test only. Throws when FRICON_TEST_FAULT=<phase>:<rank>:<kind> names `phase` and this rank of
/// MPI_COMM_WORLD (MPI must be initialized), once per process: kind "bad_alloc" throws a
/// std::bad_alloc, "numerical" a NumericalError, "generic" a std::runtime_error; the message
/// (what()) is "injected fault FRICON_TEST_FAULT=<value>". A malformed value (an unknown phase
/// or kind, a rank that is not a number) throws InputError naming it, wherever the first call
/// is made. `phase` must be one of kFaultPhases.
void test_fault(std::string_view phase);

}  // namespace fricon::parallel
