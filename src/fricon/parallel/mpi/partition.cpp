#include "fricon/parallel/mpi/partition.hpp"

#include <petscmat.h>

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/session.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

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

// The dual graph in compressed rows: the neighbours of tetrahedron t are
// adj[start[t] .. start[t + 1]), ascending.
struct DualGraph {
  std::vector<PetscInt> start, adj;
};

DualGraph dual_graph(const mesh::TetMesh& mesh) {
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
  std::vector<std::vector<Index>> neighbours(static_cast<std::size_t>(mesh.n_tets()));
  for (std::size_t i = 0; i + 1 < sides.size(); ++i)
    if (sides[i].key == sides[i + 1].key) {
      neighbours[static_cast<std::size_t>(sides[i].tet)].push_back(sides[i + 1].tet);
      neighbours[static_cast<std::size_t>(sides[i + 1].tet)].push_back(sides[i].tet);
    }
  DualGraph g;
  g.start.push_back(0);
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    g.adj.insert(g.adj.end(), n.begin(), n.end());
    g.start.push_back(static_cast<PetscInt>(g.adj.size()));
  }
  return g;
}

// What a failed MPI call was part of, for its message (check_mpi).
constexpr const char* kPartitioning = "partitioning the mesh";

// The counts and offsets of the blocks of `n` items by rank, as MPI's v-collectives take them.
struct Blocks {
  std::vector<int> counts, offsets;
};

Blocks tet_blocks(Index n, int size) {
  Blocks b;
  for (int r = 0; r < size; ++r) {
    b.offsets.push_back(static_cast<int>(block_begin(n, r, size)));
    b.counts.push_back(static_cast<int>(block_begin(n, r + 1, size) - block_begin(n, r, size)));
  }
  return b;
}

// This rank's rows of the dual graph, scattered from rank 0's whole graph, in the arrays that
// MatCreateMPIAdj takes (allocated with PetscMalloc: the matrix owns them).
struct AdjacencyRows {
  PetscInt* ia = nullptr;
  PetscInt* ja = nullptr;
};

AdjacencyRows scatter_rows(const DualGraph* g, Index n, MPI_Comm comm, int rank, int size) {
  const Blocks rows = tet_blocks(n, size);
  const int n_mine = rows.counts[static_cast<std::size_t>(rank)];
  // The degree of each tetrahedron, then the neighbours, block by block.
  std::vector<PetscInt> degree;
  Blocks edges;
  if (rank == 0) {
    for (Index t = 0; t < n; ++t)
      degree.push_back(g->start[static_cast<std::size_t>(t + 1)] -
                       g->start[static_cast<std::size_t>(t)]);
    for (int r = 0; r < size; ++r) {
      const auto lo = static_cast<std::size_t>(rows.offsets[static_cast<std::size_t>(r)]);
      const auto hi = lo + static_cast<std::size_t>(rows.counts[static_cast<std::size_t>(r)]);
      edges.offsets.push_back(static_cast<int>(g->start[lo]));
      edges.counts.push_back(static_cast<int>(g->start[hi] - g->start[lo]));
    }
  }
  std::vector<PetscInt> my_degree(static_cast<std::size_t>(n_mine));
  check_mpi(MPI_Scatterv(degree.data(), rows.counts.data(), rows.offsets.data(), MPIU_INT,
                         my_degree.data(), n_mine, MPIU_INT, 0, comm),
            "MPI_Scatterv", kPartitioning);
  AdjacencyRows a;
  check(PetscMalloc1(n_mine + 1, &a.ia), "PetscMalloc1");
  a.ia[0] = 0;
  for (int k = 0; k < n_mine; ++k)
    a.ia[k + 1] = a.ia[k] + my_degree[static_cast<std::size_t>(k)];
  check(PetscMalloc1(std::max<PetscInt>(a.ia[n_mine], 1), &a.ja), "PetscMalloc1");
  check_mpi(
      MPI_Scatterv(rank == 0 ? g->adj.data() : nullptr, edges.counts.data(), edges.offsets.data(),
                   MPIU_INT, a.ja, static_cast<int>(a.ia[n_mine]), MPIU_INT, 0, comm),
      "MPI_Scatterv", kPartitioning);
  return a;
}

// The partition of the dual graph `g` (rank 0's; freed once scattered) by PT-Scotch across the
// ranks; the owners on rank 0. Every call is collective: a failure ends the job (or_abort).
std::vector<int> partition_graph(DualGraph& g, Index n, MPI_Comm comm, int rank, int size) {
  const Blocks rows = tet_blocks(n, size);
  AdjacencyRows a = scatter_rows(rank == 0 ? &g : nullptr, n, comm, rank, size);
  g = DualGraph{};  // scattered: free it
  test_fault("partition");
  const int n_mine = rows.counts[static_cast<std::size_t>(rank)];
  Mat graph = nullptr;
  check(MatCreateMPIAdj(comm, n_mine, static_cast<PetscInt>(n), a.ia, a.ja, nullptr, &graph),
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
  std::vector<int> local(mine, mine + n_mine);
  check(ISRestoreIndices(parts, &mine), "ISRestoreIndices");
  ISDestroy(&parts);
  MatPartitioningDestroy(&part);
  MatDestroy(&graph);
  // Rank 0 gathers the owners: it gives each rank its part of the model.
  std::vector<int> owner(rank == 0 ? static_cast<std::size_t>(n) : 0);
  check_mpi(MPI_Gatherv(local.data(), n_mine, MPI_INT, owner.data(), rows.counts.data(),
                        rows.offsets.data(), MPI_INT, 0, comm),
            "MPI_Gatherv", kPartitioning);
  return owner;
}

// Collective: see partition_elements() for how it fails.
std::vector<int> graph_partition(const mesh::TetMesh* mesh, Index n, MPI_Comm comm, int rank,
                                 int size) {
  // Rank 0 alone builds the graph: agreed before the collective calls.
  DualGraph g;
  collectively([&] { g = rank == 0 ? dual_graph(*mesh) : DualGraph{}; }, comm);
  std::vector<int> owner;
  or_abort([&] { owner = partition_graph(g, n, comm, rank, size); }, comm);
  return owner;
}

}  // namespace

std::vector<int> partition_elements(const mesh::TetMesh* mesh, PartitionKind kind, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  long n = rank == 0 ? static_cast<long>(mesh->n_tets()) : 0;
  check_mpi(MPI_Bcast(&n, 1, MPI_LONG, 0, comm), "MPI_Bcast", kPartitioning);
  std::vector<int> owner;
  switch (kind) {
    case PartitionKind::Graph:
      if (size > 1) return graph_partition(mesh, n, comm, rank, size);
      break;
    case PartitionKind::Blocks:
      break;
  }
  // One rank, or blocks: rank 0 alone, agreed.
  collectively([&] { owner = rank == 0 ? blocks(n, size) : std::vector<int>{}; }, comm);
  return owner;
}

std::vector<std::vector<Index>> elements_by_rank(const std::vector<int>& owner, int size) {
  std::vector<std::vector<Index>> elements(static_cast<std::size_t>(size));
  for (std::size_t t = 0; t < owner.size(); ++t) {
    FRICON_CHECK(owner[t] >= 0 && owner[t] < size,
                 "tetrahedron " << t << " given to rank " << owner[t] << " of " << size);
    elements[static_cast<std::size_t>(owner[t])].push_back(static_cast<Index>(t));
  }
  return elements;
}

}  // namespace fricon::parallel
