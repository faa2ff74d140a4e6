#include "fricon/parallel/mpi/partition.hpp"

#include <petscmat.h>

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::parallel {

namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0)
    throw Error(fmt::format("partitioning the mesh: {} failed (PETSc error {})", what, code));
}

// Block [begin(r), begin(r + 1)) of the tetrahedra, by rank.
Index block_begin(Index n, int rank, int size) {
  return n * rank / size;
}

std::vector<int> blocks(Index n_tets, int size) {
  std::vector<int> owner(static_cast<std::size_t>(n_tets));
  for (int r = 0; r < size; ++r)
    std::fill(owner.begin() + block_begin(n_tets, r, size),
              owner.begin() + block_begin(n_tets, r + 1, size), r);
  return owner;
}

// Neighbours through faces: for each face of each tetrahedron, its sorted vertices; equal keys
// are the two sides of an interior face.
struct FaceSide {
  std::array<Index, 3> key;
  Index tet;
  bool operator<(const FaceSide& o) const { return key < o.key || (key == o.key && tet < o.tet); }
};

std::vector<std::vector<Index>> dual_graph(const mesh::TetMesh& mesh) {
  std::vector<FaceSide> sides;
  sides.reserve(static_cast<std::size_t>(4 * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> k{};
      int m = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) k[static_cast<std::size_t>(m++)] = mesh.tets(a, t);
      std::sort(k.begin(), k.end());
      sides.push_back({k, t});
    }
  std::sort(sides.begin(), sides.end());
  std::vector<std::vector<Index>> adj(static_cast<std::size_t>(mesh.n_tets()));
  for (std::size_t i = 0; i + 1 < sides.size(); ++i)
    if (sides[i].key == sides[i + 1].key) {
      adj[static_cast<std::size_t>(sides[i].tet)].push_back(sides[i + 1].tet);
      adj[static_cast<std::size_t>(sides[i + 1].tet)].push_back(sides[i].tet);
    }
  return adj;
}

std::vector<int> graph_partition(const mesh::TetMesh& mesh, MPI_Comm comm, int rank, int size) {
  const Index n = mesh.n_tets();
  const Index lo = block_begin(n, rank, size), hi = block_begin(n, rank + 1, size);
  const std::vector<std::vector<Index>> adj = dual_graph(mesh);
  // MatCreateMPIAdj takes ownership of arrays allocated with PetscMalloc.
  PetscInt *ia = nullptr, *ja = nullptr;
  Index n_edges = 0;
  for (Index t = lo; t < hi; ++t)
    n_edges += static_cast<Index>(adj[static_cast<std::size_t>(t)].size());
  check(PetscMalloc1(hi - lo + 1, &ia), "PetscMalloc1");
  check(PetscMalloc1(std::max<Index>(n_edges, 1), &ja), "PetscMalloc1");
  ia[0] = 0;
  for (Index t = lo; t < hi; ++t) {
    const auto& a = adj[static_cast<std::size_t>(t)];
    std::copy(a.begin(), a.end(), ja + ia[t - lo]);
    std::sort(ja + ia[t - lo], ja + ia[t - lo] + a.size());
    ia[t - lo + 1] = ia[t - lo] + static_cast<PetscInt>(a.size());
  }
  Mat graph = nullptr;
  check(MatCreateMPIAdj(comm, static_cast<PetscInt>(hi - lo), static_cast<PetscInt>(n), ia, ja,
                        nullptr, &graph),
        "MatCreateMPIAdj");
  MatPartitioning part = nullptr;
  IS parts = nullptr;
  check(MatPartitioningCreate(comm, &part), "MatPartitioningCreate");
  check(MatPartitioningSetAdjacency(part, graph), "MatPartitioningSetAdjacency");
  check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
  check(MatPartitioningSetNParts(part, size), "MatPartitioningSetNParts");
  check(MatPartitioningApply(part, &parts), "MatPartitioningApply");
  const PetscInt* mine = nullptr;
  check(ISGetIndices(parts, &mine), "ISGetIndices");
  std::vector<int> local(mine, mine + (hi - lo));
  check(ISRestoreIndices(parts, &mine), "ISRestoreIndices");
  ISDestroy(&parts);
  MatPartitioningDestroy(&part);
  MatDestroy(&graph);
  // Every rank gets the whole owner array (the mesh is on every rank too).
  std::vector<int> counts(static_cast<std::size_t>(size)), starts(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    starts[static_cast<std::size_t>(r)] = static_cast<int>(block_begin(n, r, size));
    counts[static_cast<std::size_t>(r)] =
        static_cast<int>(block_begin(n, r + 1, size) - block_begin(n, r, size));
  }
  std::vector<int> owner(static_cast<std::size_t>(n));
  if (MPI_Allgatherv(local.data(), static_cast<int>(local.size()), MPI_INT, owner.data(),
                     counts.data(), starts.data(), MPI_INT, comm) != MPI_SUCCESS)
    throw Error("partitioning the mesh: MPI_Allgatherv failed");
  return owner;
}

}  // namespace

std::vector<int> partition_elements(const mesh::TetMesh& mesh, PartitionKind kind, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return std::vector<int>(static_cast<std::size_t>(mesh.n_tets()), 0);
  switch (kind) {
    case PartitionKind::Graph:
      return graph_partition(mesh, comm, rank, size);
    case PartitionKind::Blocks:
      return blocks(mesh.n_tets(), size);
  }
  throw Error("partition_elements: invalid partition kind");
}

std::vector<Index> elements_of(const std::vector<int>& owner, int rank) {
  std::vector<Index> mine;
  for (std::size_t t = 0; t < owner.size(); ++t)
    if (owner[t] == rank) mine.push_back(static_cast<Index>(t));
  return mine;
}

}  // namespace fricon::parallel
