#include "fricon/feti/partition.hpp"

#ifdef FRICON_HAVE_METIS
#include <metis.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <queue>
#include <utility>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/shared_random.hpp"

namespace fricon::feti {

namespace {

// The key whose value n_subdomains is, for messages.
constexpr const char* kKey = "solver.subdomains";
// The round of METIS's first partition; a re-cut in round r seeds METIS with kMetisSeed + r.
constexpr Index kFirstRound = 0;
// A body given this many subdomains stays whole: it needs no graph partitioner.
constexpr Index kWholeBody = 1;
// The METIS part of every tetrahedron of a body that stays whole.
constexpr Index kOnlyPart = 0;

// ---------------------------------------------------------------------------------------------
// The dual graph: tetrahedra adjacent when they share a triangular face.

// One face of one tetrahedron: its three corner nodes sorted, and the tetrahedron. Equal keys are
// the two sides of an interior face.
struct FaceSide {
  std::array<Index, 3> key;
  Index tet;
  bool operator<(const FaceSide& o) const { return key < o.key || (key == o.key && tet < o.tet); }
};

// The neighbours of tetrahedron t are adjacent[start[t] .. start[t + 1]), ascending, unique.
struct DualGraph {
  std::vector<Index> start;
  std::vector<Index> adjacent;

  Index begin(Index t) const { return start[static_cast<size_t>(t)]; }
  Index end(Index t) const { return start[static_cast<size_t>(t) + 1]; }
  Index neighbour(Index q) const { return adjacent[static_cast<size_t>(q)]; }
};

std::vector<FaceSide> face_sides(const mesh::TetMesh& mesh) {
  std::vector<FaceSide> sides;
  sides.reserve(static_cast<size_t>(4 * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> key{};
      int m = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) key[static_cast<size_t>(m++)] = mesh.tets(a, t);
      std::sort(key.begin(), key.end());
      sides.push_back({key, t});
    }
  std::sort(sides.begin(), sides.end());
  return sides;
}

// From the corner nodes (mesh.tets) only, so a quadratic mesh has the graph of its corners. Every
// pair of tetrahedra on one face is an edge (a face of three or more tetrahedra, which check_mesh
// refuses, would join them all).
DualGraph dual_graph(const mesh::TetMesh& mesh) {
  const std::vector<FaceSide> sides = face_sides(mesh);
  std::vector<std::pair<Index, Index>> edges;  // both directions
  for (size_t first = 0, last = 0; first < sides.size(); first = last) {
    last = first + 1;
    while (last < sides.size() && sides[last].key == sides[first].key)
      ++last;
    for (size_t i = first; i < last; ++i)
      for (size_t j = first; j < last; ++j)
        if (sides[i].tet != sides[j].tet) edges.emplace_back(sides[i].tet, sides[j].tet);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  DualGraph g;
  g.start.assign(static_cast<size_t>(mesh.n_tets()) + 1, 0);
  for (const auto& [t, u] : edges)
    ++g.start[static_cast<size_t>(t) + 1];
  for (size_t t = 0; t + 1 < g.start.size(); ++t)
    g.start[t + 1] += g.start[t];
  g.adjacent.reserve(edges.size());
  for (const auto& [t, u] : edges)
    g.adjacent.push_back(u);
  return g;
}

// ---------------------------------------------------------------------------------------------
// The request and its distribution over the bodies.

}  // namespace

void check_subdomain_count(const mesh::TetMesh& mesh, Index n_subdomains,
                           const std::string& key_context) {
  if (n_subdomains < 1)
    throw InputError(fmt::format("{}: {} = {}: the number of subdomains must be at least 1",
                                 key_context, kKey, n_subdomains));
  if (n_subdomains > mesh.n_tets())
    throw InputError(fmt::format(
        "{}: {} = {} is more than the {} tetrahedra of the mesh: each subdomain needs at least "
        "one tetrahedron, so at most {} subdomains",
        key_context, kKey, n_subdomains, mesh.n_tets(), mesh.n_tets()));
}

namespace {

// The subdomains of each body: 1 each, then one by one to the body whose subdomains are the
// largest (most tetrahedra per subdomain; the first such body on a tie), which keeps the largest
// subdomain as small as the counts allow. A body never gets more subdomains than tetrahedra when
// the total does not exceed the mesh's (it would take one when every body has as many
// subdomains as tetrahedra).
std::vector<Index> distribute(const mesh::Bodies& bodies, Index n_subdomains) {
  const Index n_bodies = bodies.n_bodies();
  std::vector<Index> share(static_cast<size_t>(n_bodies), kWholeBody);
  const auto n_tets = [&](Index b) {
    return static_cast<Index>(bodies.tets[static_cast<size_t>(b)].size());
  };
  // True when body a's subdomains are smaller than b's, or as large and a comes after b: the
  // top of the queue is the body to give the next subdomain.
  const auto after = [&](Index a, Index b) {
    const Index lhs = n_tets(a) * share[static_cast<size_t>(b)];
    const Index rhs = n_tets(b) * share[static_cast<size_t>(a)];
    return lhs < rhs || (lhs == rhs && a > b);
  };
  std::priority_queue<Index, std::vector<Index>, decltype(after)> next(after);
  for (Index b = 0; b < n_bodies; ++b)
    next.push(b);
  for (Index given = n_bodies; given < n_subdomains; ++given) {
    const Index b = next.top();
    next.pop();
    ++share[static_cast<size_t>(b)];
    next.push(b);
  }
  for (Index b = 0; b < n_bodies; ++b)
    FRICON_CHECK(share[static_cast<size_t>(b)] <= n_tets(b),
                 "body " << b << " of " << n_tets(b) << " tetrahedra given "
                         << share[static_cast<size_t>(b)] << " subdomains");
  return share;
}

// ---------------------------------------------------------------------------------------------
// The parts of one body, and their face-connected pieces.

// One body: its tetrahedra (ascending), and the position of each tetrahedron of the mesh in its
// body's list (local numbering).
struct BodyView {
  Index body = 0;
  const std::vector<Index>& tets;
  const std::vector<Index>& local;
  const std::vector<Index>& tet_body;

  Index n_tets() const { return static_cast<Index>(tets.size()); }
  Index local_of(Index t) const { return local[static_cast<size_t>(t)]; }
  bool holds(Index t) const { return tet_body[static_cast<size_t>(t)] == body; }
};

// The face-connected pieces of the parts of a body: two tetrahedra are in one piece when a chain
// of tetrahedra of the same part (part[local index]), each sharing a face with the next, joins
// them. Each piece's tetrahedra ascending (global indices), the pieces in the order of their
// first tetrahedron; piece_part gets the part of each.
std::vector<std::vector<Index>> face_connected_pieces(const BodyView& body, const DualGraph& graph,
                                                      const std::vector<Index>& part,
                                                      std::vector<Index>& piece_part) {
  std::vector<std::vector<Index>> pieces;
  piece_part.clear();
  std::vector<bool> reached(static_cast<size_t>(body.n_tets()), false);
  std::vector<Index> stack;
  for (Index seed = 0; seed < body.n_tets(); ++seed) {
    if (reached[static_cast<size_t>(seed)]) continue;
    const Index label = part[static_cast<size_t>(seed)];
    std::vector<Index> piece;
    reached[static_cast<size_t>(seed)] = true;
    stack.push_back(body.tets[static_cast<size_t>(seed)]);
    while (!stack.empty()) {
      const Index t = stack.back();
      stack.pop_back();
      piece.push_back(t);
      for (Index q = graph.begin(t); q < graph.end(t); ++q) {
        const Index u = graph.neighbour(q);
        if (!body.holds(u)) continue;
        const auto i = static_cast<size_t>(body.local_of(u));
        if (reached[i] || part[i] != label) continue;
        reached[i] = true;
        stack.push_back(u);
      }
    }
    std::sort(piece.begin(), piece.end());
    pieces.push_back(std::move(piece));
    piece_part.push_back(label);
  }
  return pieces;
}

#ifdef FRICON_HAVE_METIS

// The number of face-connected pieces of the whole body.
Index count_face_connected_pieces(const BodyView& body, const DualGraph& graph) {
  std::vector<Index> piece_part;
  const std::vector<Index> one_part(static_cast<size_t>(body.n_tets()), kOnlyPart);
  return static_cast<Index>(face_connected_pieces(body, graph, one_part, piece_part).size());
}

// The seed of METIS's random choices (matchings of the coarsening, initial partitions): fixed, so
// that a mesh gives the same partition on every run.
constexpr idx_t kMetisSeed = 20240601;
// The number of balance constraints of the vertices (METIS's ncon): one, the tetrahedra.
constexpr idx_t kOneConstraint = 1;

// n as METIS's index type, or an InputError when it does not fit (idx_t is 32-bit on Debian).
idx_t to_idx(Index n, const BodyView& body, const std::string& key_context) {
  if (n > static_cast<Index>(std::numeric_limits<idx_t>::max()))
    throw InputError(fmt::format(
        "{}: {}: body {} ({} tetrahedra) is too large for the METIS of this build, whose "
        "{}-bit indices stop at {}",
        key_context, kKey, body.body, body.n_tets(), IDXTYPEWIDTH,
        std::numeric_limits<idx_t>::max()));
  return static_cast<idx_t>(n);
}

// The dual graph of one body in METIS's compressed rows, local numbering.
struct MetisGraph {
  std::vector<idx_t> xadj;
  std::vector<idx_t> adjncy;
};

MetisGraph metis_graph(const BodyView& body, const DualGraph& graph,
                       const std::string& key_context) {
  to_idx(body.n_tets(), body, key_context);  // then every local index fits
  MetisGraph g;
  g.xadj.reserve(static_cast<size_t>(body.n_tets()) + 1);
  g.xadj.push_back(0);
  for (Index t : body.tets) {
    for (Index q = graph.begin(t); q < graph.end(t); ++q)
      if (body.holds(graph.neighbour(q)))
        g.adjncy.push_back(static_cast<idx_t>(body.local_of(graph.neighbour(q))));
    g.xadj.push_back(to_idx(static_cast<Index>(g.adjncy.size()), body, key_context));
  }
  return g;
}

// METIS_PartGraphKway of the body's graph into n_parts parts (edge cut minimised), contiguous
// parts asked for when `contiguous`; returns METIS's status and the part of each tetrahedron.
int call_metis(MetisGraph& g, idx_t n_parts, bool contiguous, idx_t seed,
               std::vector<idx_t>& part) {
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = seed;
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_CONTIG] = contiguous ? 1 : 0;
  idx_t n_vertices = static_cast<idx_t>(g.xadj.size()) - 1;
  idx_t n_constraints = kOneConstraint;
  idx_t edge_cut = 0;
  idx_t no_edge = 0;  // a valid pointer for a body whose tetrahedra share no face
  part.assign(static_cast<size_t>(n_vertices), 0);
  // METIS seeds and draws from the C library's random sequence (core/shared_random.hpp).
  const std::lock_guard random_lock(shared_random_mutex());
  return METIS_PartGraphKway(&n_vertices, &n_constraints, g.xadj.data(),
                             g.adjncy.empty() ? &no_edge : g.adjncy.data(), nullptr, nullptr,
                             nullptr, &n_parts, nullptr, nullptr, options, &edge_cut, part.data());
}

// The METIS part of each tetrahedron of the body (local numbering), for n_parts > 1 parts.
// Contiguous parts are asked for when the body is face-connected (METIS refuses the option on a
// graph that is not, with a message on stderr), and asked again without if METIS fails with it.
std::vector<Index> metis_parts(const BodyView& body, const DualGraph& graph, Index n_parts,
                               const std::string& key_context, Index round) {
  MetisGraph g = metis_graph(body, graph, key_context);
  const idx_t parts = to_idx(n_parts, body, key_context);
  const bool connected = count_face_connected_pieces(body, graph) == 1;
  const auto seed = static_cast<idx_t>(kMetisSeed + round);
  std::vector<idx_t> part;
  int status = call_metis(g, parts, connected, seed, part);
  if (status != METIS_OK && connected) status = call_metis(g, parts, false, seed, part);
  if (status != METIS_OK)
    throw Error(fmt::format(
        "partitioning body {} ({} tetrahedra) into {} subdomains: METIS_PartGraphKway failed "
        "(METIS status {})",
        body.body, body.n_tets(), n_parts, status));
  std::vector<Index> labels(part.begin(), part.end());
  for (Index label : labels)
    FRICON_CHECK(label >= 0 && label < n_parts, "METIS part " << label << " of " << n_parts);
  return labels;
}

#else

std::vector<Index> metis_parts(const BodyView& body, const DualGraph&, Index n_parts,
                               const std::string& key_context, Index) {
  throw InputError(fmt::format(
      "{}: {}: backend \"tfeti\" needs METIS to cut body {} into {} subdomains, and this fricon "
      "was built without it: install the Debian package libmetis-dev and build fricon again "
      "(or ask for one subdomain per body)",
      key_context, kKey, body.body, n_parts));
}

#endif

// The part of each tetrahedron of the body (local numbering): all one part for a body that
// stays whole, else METIS's.
std::vector<Index> body_parts(const BodyView& body, const DualGraph& graph, Index n_parts,
                              const std::string& key_context) {
  if (n_parts == kWholeBody)
    return std::vector<Index>(static_cast<size_t>(body.n_tets()), kOnlyPart);
  return metis_parts(body, graph, n_parts, key_context, kFirstRound);
}

// ---------------------------------------------------------------------------------------------
// The partition of the mesh, and what was adjusted.

// What changed between the parts and the subdomains, over all bodies.
struct Adjustments {
  Index n_split = 0;         // parts in several pieces
  Index n_split_pieces = 0;  // the pieces of those parts
  Index n_empty = 0;         // parts without tetrahedra
};

// Records the pieces of one body's n_parts parts: how many parts were split, how many empty.
void count_adjustments(const std::vector<Index>& piece_part, Index n_parts, Adjustments& adjust) {
  std::vector<Index> pieces_of_part(static_cast<size_t>(n_parts), 0);
  for (Index p : piece_part)
    ++pieces_of_part[static_cast<size_t>(p)];
  for (Index count : pieces_of_part) {
    if (count == 0) ++adjust.n_empty;
    if (count > 1) {
      ++adjust.n_split;
      adjust.n_split_pieces += count;
    }
  }
}

// "1 part was", "3 parts were".
std::string parts_were(Index n) {
  return fmt::format("{} part{} {}", n, n == 1 ? "" : "s", n == 1 ? "was" : "were");
}

std::string adjustment_note(Index requested, Index n_bodies, Index n_subdomains,
                            const Adjustments& adjust) {
  std::vector<std::string> reasons;
  if (requested < n_bodies)
    reasons.push_back(
        fmt::format("the mesh has {} bodies and a subdomain lies in one body", n_bodies));
  if (adjust.n_split > 0)
    reasons.push_back(fmt::format("{} not face-connected and split into {} face-connected pieces",
                                  parts_were(adjust.n_split), adjust.n_split_pieces));
  if (adjust.n_empty > 0)
    reasons.push_back(
        fmt::format("{} left empty by METIS and dropped", parts_were(adjust.n_empty)));
  if (reasons.empty()) return "";
  std::string why;
  for (size_t i = 0; i < reasons.size(); ++i)
    why += (i == 0 ? "" : i + 1 == reasons.size() ? ", and " : ", ") + reasons[i];
  return fmt::format("{} = {} gave {} subdomain{}: {}.", kKey, requested, n_subdomains,
                     n_subdomains == 1 ? "" : "s", why);
}

// The position of each tetrahedron in its body's list.
std::vector<Index> local_numbering(const mesh::TetMesh& mesh, const mesh::Bodies& bodies) {
  std::vector<Index> local(static_cast<size_t>(mesh.n_tets()), -1);
  for (const auto& tets : bodies.tets)
    for (size_t i = 0; i < tets.size(); ++i)
      local[static_cast<size_t>(tets[i])] = static_cast<Index>(i);
  return local;
}

void add_subdomain(Partition& partition, std::vector<Index> tets) {
  for (Index t : tets)
    partition.subdomain_of_tet[static_cast<size_t>(t)] = partition.n_subdomains;
  partition.tets.push_back(std::move(tets));
  ++partition.n_subdomains;
}

}  // namespace

Index subdomains_for_size(const mesh::TetMesh& mesh, Index subdomain_size) {
  FRICON_CHECK(subdomain_size >= 1, "subdomain size " << subdomain_size);
  const auto nearest = static_cast<Index>(
      std::llround(static_cast<double>(mesh.n_nodes()) / static_cast<double>(subdomain_size)));
  return std::max(Index{1}, std::min(nearest, mesh.n_tets()));
}

Partition partition_mesh(const mesh::TetMesh& mesh, const mesh::Bodies& bodies, Index n_subdomains,
                         const std::string& key_context) {
  FRICON_CHECK(static_cast<Index>(bodies.tet_body.size()) == mesh.n_tets(),
               "bodies of " << bodies.tet_body.size() << " tetrahedra, mesh of " << mesh.n_tets());
  check_subdomain_count(mesh, n_subdomains, key_context);
  const std::vector<Index> share = distribute(bodies, n_subdomains);
  const DualGraph graph = dual_graph(mesh);
  const std::vector<Index> local = local_numbering(mesh, bodies);

  Partition partition;
  partition.subdomain_of_tet.assign(static_cast<size_t>(mesh.n_tets()), -1);
  Adjustments adjust;
  std::vector<Index> piece_part;
  for (Index b = 0; b < bodies.n_bodies(); ++b) {
    const BodyView body{b, bodies.tets[static_cast<size_t>(b)], local, bodies.tet_body};
    const Index n_parts = share[static_cast<size_t>(b)];
    const std::vector<Index> part = body_parts(body, graph, n_parts, key_context);
    for (std::vector<Index>& piece : face_connected_pieces(body, graph, part, piece_part))
      add_subdomain(partition, std::move(piece));
    count_adjustments(piece_part, n_parts, adjust);
  }
  partition.n_split = adjust.n_split;
  partition.note = adjustment_note(n_subdomains, bodies.n_bodies(), partition.n_subdomains, adjust);
  return partition;
}

namespace {

// The subdomains of `partition` that share a face with subdomain s (s excluded), ascending.
std::vector<Index> face_neighbours(const Partition& partition, const DualGraph& graph, Index s) {
  std::vector<Index> next;
  for (Index t : partition.tets[static_cast<size_t>(s)])
    for (Index q = graph.begin(t); q < graph.end(t); ++q) {
      const Index other = partition.subdomain_of_tet[static_cast<size_t>(graph.neighbour(q))];
      if (other != s) next.push_back(other);
    }
  std::sort(next.begin(), next.end());
  next.erase(std::unique(next.begin(), next.end()), next.end());
  return next;
}

// The regions to cut again: each necked subdomain with its face neighbours, regions that share a
// subdomain merged (union-find over the subdomains). Per subdomain its region's root, -1 outside.
std::vector<Index> recut_regions(const Partition& partition, const DualGraph& graph,
                                 const std::vector<Index>& necked) {
  std::vector<Index> root(static_cast<size_t>(partition.n_subdomains), -1);
  const auto find = [&root](Index s) {
    while (root[static_cast<size_t>(s)] != s)
      s = root[static_cast<size_t>(s)] = root[static_cast<size_t>(root[static_cast<size_t>(s)])];
    return s;
  };
  for (Index s : necked) {
    if (root[static_cast<size_t>(s)] < 0) root[static_cast<size_t>(s)] = s;
    for (Index other : face_neighbours(partition, graph, s)) {
      if (root[static_cast<size_t>(other)] < 0) root[static_cast<size_t>(other)] = other;
      root[static_cast<size_t>(find(other))] = find(s);
    }
  }
  for (Index s = 0; s < partition.n_subdomains; ++s)
    if (root[static_cast<size_t>(s)] >= 0) root[static_cast<size_t>(s)] = find(s);
  return root;
}

}  // namespace

Partition recut_necked(const mesh::TetMesh& mesh, const mesh::Bodies& bodies,
                       const Partition& partition, const std::vector<Index>& necked, Index round,
                       const std::string& key_context) {
  if (necked.empty()) return partition;
  const DualGraph graph = dual_graph(mesh);
  const std::vector<Index> region_of = recut_regions(partition, graph, necked);
  // @sect: the subdomains outside every region stay as they are.
  std::vector<std::vector<Index>> kept_or_new;
  std::vector<Index> roots;
  for (Index s = 0; s < partition.n_subdomains; ++s) {
    const Index r = region_of[static_cast<size_t>(s)];
    if (r < 0)
      kept_or_new.push_back(partition.tets[static_cast<size_t>(s)]);
    else if (r == s)
      roots.push_back(r);
  }
  // @sect: each region cut by METIS into as many parts as it had, with another seed. A region
  // lies in one body (subdomains of two bodies share no face), which BodyView's "body" stands
  // for here: the region's root.
  std::vector<Index> tet_region(static_cast<size_t>(mesh.n_tets()), -1);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    tet_region[static_cast<size_t>(t)] =
        region_of[static_cast<size_t>(partition.subdomain_of_tet[static_cast<size_t>(t)])];
  std::vector<Index> local(static_cast<size_t>(mesh.n_tets()), -1);
  Partition result;
  result.n_split = partition.n_split;
  std::vector<Index> piece_part;
  for (Index r : roots) {
    std::vector<Index> tets;
    Index n_parts = 0;
    for (Index s = 0; s < partition.n_subdomains; ++s)
      if (region_of[static_cast<size_t>(s)] == r) {
        ++n_parts;
        tets.insert(tets.end(), partition.tets[static_cast<size_t>(s)].begin(),
                    partition.tets[static_cast<size_t>(s)].end());
      }
    if (n_parts == kWholeBody) {  // alone in its body: no neighbour to share the cut with
      kept_or_new.push_back(std::move(tets));
      continue;
    }
    std::sort(tets.begin(), tets.end());
    for (size_t i = 0; i < tets.size(); ++i)
      local[static_cast<size_t>(tets[i])] = static_cast<Index>(i);
    const BodyView region{r, tets, local, tet_region};
    const std::vector<Index> part = metis_parts(region, graph, n_parts, key_context, round);
    for (std::vector<Index>& piece : face_connected_pieces(region, graph, part, piece_part))
      kept_or_new.push_back(std::move(piece));
    Adjustments adjust;
    count_adjustments(piece_part, n_parts, adjust);
    result.n_split += adjust.n_split;
  }
  // @sect: numbered as partition_mesh numbers them: body by body, then by first tetrahedron.
  const auto order = [&bodies](const std::vector<Index>& tets) {
    return std::make_pair(bodies.tet_body[static_cast<size_t>(tets.front())], tets.front());
  };
  std::sort(kept_or_new.begin(), kept_or_new.end(),
            [&order](const std::vector<Index>& a, const std::vector<Index>& b) {
              return order(a) < order(b);
            });
  result.subdomain_of_tet.assign(static_cast<size_t>(mesh.n_tets()), -1);
  for (std::vector<Index>& tets : kept_or_new)
    add_subdomain(result, std::move(tets));
  result.note = partition.note;
  return result;
}

}  // namespace fricon::feti
