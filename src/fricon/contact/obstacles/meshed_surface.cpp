// contact: the rigid obstacle of a meshed surface (theory.md §2.11): the exact distance to its
// triangles, found in a bounding volume hierarchy, signed by the angle-weighted pseudo-normal of
// the nearest feature (meshed_surface.hpp).
#include "fricon/contact/obstacles/meshed_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

using Points = Eigen::Matrix<Real, 3, Eigen::Dynamic>;
using Triangles = Eigen::Matrix<Index, 3, Eigen::Dynamic>;

// A triangle is degenerate when twice its area is below this times its longest edge squared.
constexpr Real kDegenerateArea = 1e-12;
// x is on the surface when its distance is below this times the surface's size (the diagonal of
// its bounding box): its normal is then that of its nearest triangle.
constexpr Real kOnSurface = 1e-12;
// Triangles per leaf of the bounding volume hierarchy.
constexpr Index kLeafSize = 4;

// @sect: the nearest point of one triangle.

// The part of a triangle a point is nearest to: its inside, one of its edges (edge k joins
// vertices k and k+1 mod 3), or one of its vertices.
enum class Feature { Face, Edge, Vertex };

struct TrianglePoint {
  Vec3 point;
  Feature feature = Feature::Face;
  int which = 0;  // the edge or vertex, 0..2
};

// The point of triangle (a, b, c) nearest to x and the feature it lies on, by the Voronoi
// regions of the triangle (C. Ericson, Real-Time Collision Detection, 2005, §5.1.5).
TrianglePoint nearest_on_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ax = x - a;
  const Real d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, Feature::Vertex, 0};
  const Vec3 bx = x - b;
  const Real d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0.0 && d4 <= d3) return {b, Feature::Vertex, 1};
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {a + d1 / (d1 - d3) * ab, Feature::Edge, 0};
  const Vec3 cx = x - c;
  const Real d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0.0 && d5 <= d6) return {c, Feature::Vertex, 2};
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {a + d2 / (d2 - d6) * ac, Feature::Edge, 2};
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return {b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), Feature::Edge, 1};
  const Real scale = 1.0 / (va + vb + vc);
  return {a + ab * (vb * scale) + ac * (vc * scale), Feature::Face, 0};
}

// @sect: the triangles' connectivity.

// For each edge k of each triangle t (slot 3 t + k), the other triangle on it and that triangle's
// slot, or -1 on the rim of an open surface.
struct Adjacency {
  std::vector<Index> neighbour;  // slot -> slot of the same edge in the other triangle, or -1
};

Index slot(Index t, int k) {
  return 3 * t + k;
}

// The adjacency of `triangles`; throws InputError when an edge is in three or more triangles.
Adjacency edge_adjacency(const Triangles& triangles, const std::string& what) {
  struct EdgeRef {
    std::pair<Index, Index> key;
    Index slot;
  };
  std::vector<EdgeRef> edges;
  edges.reserve(static_cast<size_t>(3 * triangles.cols()));
  for (Index t = 0; t < triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = triangles(k, t), b = triangles((k + 1) % 3, t);
      edges.push_back({{std::min(a, b), std::max(a, b)}, slot(t, k)});
    }
  std::sort(edges.begin(), edges.end(), [](const EdgeRef& e, const EdgeRef& f) {
    return e.key < f.key || (e.key == f.key && e.slot < f.slot);
  });
  Adjacency adjacency{std::vector<Index>(edges.size(), -1)};
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key)
      ++j;
    if (j - i > 2)
      throw InputError(fmt::format(
          "{} is not a manifold surface: the edge between its points {} and {} is in {} "
          "triangles (at most two may share an edge)",
          what, edges[i].key.first, edges[i].key.second, j - i));
    if (j - i == 2) {
      adjacency.neighbour[static_cast<size_t>(edges[i].slot)] = edges[i + 1].slot;
      adjacency.neighbour[static_cast<size_t>(edges[i + 1].slot)] = edges[i].slot;
    }
    i = j;
  }
  return adjacency;
}

Index find_root(std::vector<Index>& parent, Index i) {
  while (parent[static_cast<size_t>(i)] != i) {
    parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    i = parent[static_cast<size_t>(i)];
  }
  return i;
}

// Throws InputError when the triangles around some point form two or more fans that share no
// edge (two sheets, or two closed surfaces, touching at a point).
void require_manifold_vertices(const Triangles& triangles, const Adjacency& adjacency,
                               Index n_points, const std::string& what) {
  // Corner 3 t + k is vertex k of triangle t; corners of one point joined across shared edges.
  std::vector<Index> parent(static_cast<size_t>(3 * triangles.cols()));
  std::iota(parent.begin(), parent.end(), Index{0});
  const auto join = [&parent](Index i, Index j) {
    parent[static_cast<size_t>(find_root(parent, i))] = find_root(parent, j);
  };
  for (Index t = 0; t < triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index other = adjacency.neighbour[static_cast<size_t>(slot(t, k))];
      if (other < 0) continue;
      const Index u = other / 3;
      for (int end : {k, (k + 1) % 3}) {
        const Index point = triangles(end, t);
        for (int l = 0; l < 3; ++l)
          if (triangles(l, u) == point) join(slot(t, end), slot(u, l));
      }
    }
  std::vector<Index> fan(static_cast<size_t>(n_points), -1);
  for (Index t = 0; t < triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index point = triangles(k, t);
      const Index root = find_root(parent, slot(t, k));
      Index& first = fan[static_cast<size_t>(point)];
      if (first < 0)
        first = root;
      else if (first != root)
        throw InputError(fmt::format(
            "{} is not a manifold surface: at its point {} two fans of triangles meet that share "
            "no edge",
            what, point));
    }
}

// @sect: orientation.

struct Components {
  std::vector<Index> of;     // component of each triangle
  std::vector<Index> first;  // first triangle of each component
};

// Flips triangles (swapping their last two vertices) so that every two triangles that share an
// edge run through it in opposite directions, keeping the orientation of each component's first
// triangle. Throws InputError for a component that cannot be oriented.
Components orient_consistently(Triangles& triangles, const Adjacency& adjacency,
                               const std::string& what) {
  const Index n = triangles.cols();
  Components components{std::vector<Index>(static_cast<size_t>(n), -1), {}};
  std::vector<char> flipped(static_cast<size_t>(n), 0);
  std::vector<Index> queue;
  for (Index seed = 0; seed < n; ++seed) {
    if (components.of[static_cast<size_t>(seed)] >= 0) continue;
    const Index c = static_cast<Index>(components.first.size());
    components.first.push_back(seed);
    components.of[static_cast<size_t>(seed)] = c;
    queue.assign(1, seed);
    while (!queue.empty()) {
      const Index t = queue.back();
      queue.pop_back();
      for (int k = 0; k < 3; ++k) {
        const Index other = adjacency.neighbour[static_cast<size_t>(slot(t, k))];
        if (other < 0) continue;
        const Index u = other / 3;
        // In the file, t and u run through the edge in the same direction when they start it at
        // the same point.
        const bool same = triangles(k, t) == triangles(static_cast<Index>(other % 3), u);
        const char wanted = static_cast<char>(flipped[static_cast<size_t>(t)] ^ (same ? 1 : 0));
        if (components.of[static_cast<size_t>(u)] < 0) {
          components.of[static_cast<size_t>(u)] = c;
          flipped[static_cast<size_t>(u)] = wanted;
          queue.push_back(u);
        } else if (flipped[static_cast<size_t>(u)] != wanted) {
          throw InputError(fmt::format(
              "{} cannot be oriented (a Moebius strip): its triangles {} and {} cannot both face "
              "the same side",
              what, t, u));
        }
      }
    }
  }
  for (Index t = 0; t < n; ++t)
    if (flipped[static_cast<size_t>(t)]) std::swap(triangles(1, t), triangles(2, t));
  return components;
}

void flip_components(Triangles& triangles, const Components& components,
                     const std::vector<char>& flip) {
  for (Index t = 0; t < triangles.cols(); ++t)
    if (flip[static_cast<size_t>(components.of[static_cast<size_t>(t)])])
      std::swap(triangles(1, t), triangles(2, t));
}

// @sect: the obstacle.

// An axis-aligned box.
struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<Real>::infinity());
  void add(const Vec3& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  void add(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  // Squared distance from x to the box (0 inside).
  Real squared_distance(const Vec3& x) const {
    return (lo - x).cwiseMax(x - hi).cwiseMax(0.0).squaredNorm();
  }
};

// The nearest point of the surface to a point.
struct Nearest {
  Index triangle = -1;
  TrianglePoint on;
  Real squared_distance = std::numeric_limits<Real>::infinity();
};

class MeshedSurface final : public Obstacle {
 public:
  MeshedSurface(Points points, Triangles triangles)
      : points_(std::move(points)), triangles_(std::move(triangles)) {
    for (Index p = 0; p < points_.cols(); ++p)
      bounds_.add(points_.col(p));
    on_surface_ = kOnSurface * (bounds_.hi - bounds_.lo).norm();
    build_hierarchy();
    compute_normals();
  }

  Proximity closest(const Vec3& x) const override {
    const Nearest n = nearest(x);
    const Real distance = std::sqrt(n.squared_distance);
    const Real sign = side(x, n) >= 0.0 ? 1.0 : -1.0;
    const Vec3& face = face_normal_[static_cast<size_t>(n.triangle)];
    if (distance <= on_surface_ || n.on.feature == Feature::Face)
      return {sign * distance, face};  // inside a triangle, x - p is along its normal
    return {sign * distance, Vec3(sign * (x - n.on.point) / distance)};
  }
  std::string_view kind() const override { return "surface"; }
  ObstacleSurface picture(const Vec3&, Real) const override { return {points_, triangles_}; }
  std::vector<ObstacleParameter> parameters() const override {
    return {
        {"triangles", {static_cast<Real>(triangles_.cols())}, false},
        {"bounding_box",
         {bounds_.lo(0), bounds_.lo(1), bounds_.lo(2), bounds_.hi(0), bounds_.hi(1), bounds_.hi(2)},
         false}};
  }

  // The nearest point of the triangles to x.
  Nearest nearest(const Vec3& x) const {
    Nearest best;
    std::array<Index, 64> stack{};  // the hierarchy is balanced: depth about log2(m / kLeafSize)
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<size_t>(stack[--top])];
      if (node.box.squared_distance(x) >= best.squared_distance) continue;
      if (node.count > 0) {
        for (Index i = node.first; i < node.first + node.count; ++i) {
          const Index t = order_[static_cast<size_t>(i)];
          const TrianglePoint on = nearest_on_triangle(x, vertex(t, 0), vertex(t, 1), vertex(t, 2));
          const Real d2 = (x - on.point).squaredNorm();
          if (d2 < best.squared_distance) best = {t, on, d2};
        }
        continue;
      }
      // The nearer child is searched first: pushed last.
      const Index a = node.first, b = node.first + 1;
      const bool a_nearer = nodes_[static_cast<size_t>(a)].box.squared_distance(x) <=
                            nodes_[static_cast<size_t>(b)].box.squared_distance(x);
      stack[top++] = a_nearer ? b : a;
      stack[top++] = a_nearer ? a : b;
    }
    return best;
  }

  // (x - p) . N for the nearest point p and the pseudo-normal N of its feature: >= 0 outside.
  Real side(const Vec3& x, const Nearest& n) const {
    const size_t t = static_cast<size_t>(n.triangle);
    const Vec3 r = x - n.on.point;
    switch (n.on.feature) {
      case Feature::Face:
        return r.dot(face_normal_[t]);
      case Feature::Edge:
        return r.dot(edge_normal_[3 * t + static_cast<size_t>(n.on.which)]);
      case Feature::Vertex:
        return r.dot(vertex_normal_[static_cast<size_t>(triangles_(n.on.which, n.triangle))]);
    }
    return 0.0;
  }

  Real on_surface() const { return on_surface_; }

  // Reverses the triangles t with which[component[t]] (the hierarchy stays as it is).
  void flip(const Components& components, const std::vector<char>& which) {
    flip_components(triangles_, components, which);
    compute_normals();
  }

  const Points& points() const { return points_; }
  const Triangles& triangles() const { return triangles_; }

 private:
  // A node of the hierarchy: a leaf holds order_[first, first + count); an inner node (count 0)
  // has its children at first and first + 1.
  struct Node {
    Box box;
    Index first = 0;
    Index count = 0;
  };

  Vec3 vertex(Index t, int k) const { return points_.col(triangles_(k, t)); }

  // Median splits along the longest axis of the triangles' centres.
  void build_hierarchy() {
    const Index m = triangles_.cols();
    order_.resize(static_cast<size_t>(m));
    std::iota(order_.begin(), order_.end(), Index{0});
    std::vector<Box> boxes(static_cast<size_t>(m));
    std::vector<Vec3> centres(static_cast<size_t>(m));
    for (Index t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k)
        boxes[static_cast<size_t>(t)].add(vertex(t, k));
      centres[static_cast<size_t>(t)] = (vertex(t, 0) + vertex(t, 1) + vertex(t, 2)) / 3.0;
    }
    nodes_.clear();
    nodes_.reserve(static_cast<size_t>(2 * (m / kLeafSize + 1)));
    nodes_.push_back({});
    struct Pending {
      Index node, first, count;
    };
    std::vector<Pending> pending{{0, 0, m}};
    while (!pending.empty()) {
      const Pending p = pending.back();
      pending.pop_back();
      Box box, centre_box;
      for (Index i = p.first; i < p.first + p.count; ++i) {
        const size_t t = static_cast<size_t>(order_[static_cast<size_t>(i)]);
        box.add(boxes[t]);
        centre_box.add(centres[t]);
      }
      nodes_[static_cast<size_t>(p.node)].box = box;
      if (p.count <= kLeafSize) {
        nodes_[static_cast<size_t>(p.node)].first = p.first;
        nodes_[static_cast<size_t>(p.node)].count = p.count;
        continue;
      }
      int axis = 0;
      (centre_box.hi - centre_box.lo).maxCoeff(&axis);
      const Index half = p.count / 2;
      const auto begin = order_.begin() + p.first;
      std::nth_element(begin, begin + half, begin + p.count, [&](Index s, Index t) {
        return centres[static_cast<size_t>(s)](axis) < centres[static_cast<size_t>(t)](axis);
      });
      const Index children = static_cast<Index>(nodes_.size());
      nodes_[static_cast<size_t>(p.node)].first = children;
      nodes_.push_back({});
      nodes_.push_back({});
      pending.push_back({children, p.first, half});
      pending.push_back({children + 1, p.first + half, p.count - half});
    }
  }

  // The unit normal of each triangle, and the angle-weighted pseudo-normals of the edges (the sum
  // of the normals of their triangles) and of the points (the sum of the normals of their
  // triangles, each times the triangle's angle there).
  void compute_normals() {
    const Index m = triangles_.cols();
    face_normal_.assign(static_cast<size_t>(m), Vec3::Zero());
    for (Index t = 0; t < m; ++t)
      face_normal_[static_cast<size_t>(t)] =
          (vertex(t, 1) - vertex(t, 0)).cross(vertex(t, 2) - vertex(t, 0)).normalized();
    const Adjacency adjacency = edge_adjacency(triangles_, "");
    edge_normal_.assign(static_cast<size_t>(3 * m), Vec3::Zero());
    vertex_normal_.assign(static_cast<size_t>(points_.cols()), Vec3::Zero());
    for (Index t = 0; t < m; ++t) {
      const Vec3& n = face_normal_[static_cast<size_t>(t)];
      for (int k = 0; k < 3; ++k) {
        const Index other = adjacency.neighbour[static_cast<size_t>(slot(t, k))];
        edge_normal_[static_cast<size_t>(slot(t, k))] =
            other < 0 ? n : Vec3(n + face_normal_[static_cast<size_t>(other / 3)]);
        const Vec3 e1 = vertex(t, (k + 1) % 3) - vertex(t, k);
        const Vec3 e2 = vertex(t, (k + 2) % 3) - vertex(t, k);
        const Real angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
        vertex_normal_[static_cast<size_t>(triangles_(k, t))] += angle * n;
      }
    }
  }

  Points points_;
  Triangles triangles_;
  Box bounds_;
  Real on_surface_ = 0.0;
  std::vector<Node> nodes_;
  std::vector<Index> order_;  // triangles in the order of the leaves
  std::vector<Vec3> face_normal_;
  std::vector<Vec3> edge_normal_;    // slot 3 t + k: edge k of triangle t
  std::vector<Vec3> vertex_normal_;  // of each point
};

// @sect: checks of the input.

void require_valid_input(const mesh::RigidSurface& surface, const std::string& what) {
  if (surface.triangles.cols() == 0) throw InputError(fmt::format("{} has no triangle", what));
  if (!surface.points.allFinite())
    throw InputError(fmt::format("{} has a non-finite coordinate", what));
  for (Index t = 0; t < surface.triangles.cols(); ++t) {
    for (int k = 0; k < 3; ++k)
      if (surface.triangles(k, t) < 0 || surface.triangles(k, t) >= surface.points.cols())
        throw InputError(fmt::format("{}: triangle {} refers to point {}, but it has {} points",
                                     what, t, surface.triangles(k, t), surface.points.cols()));
    const Vec3 a = surface.points.col(surface.triangles(0, t));
    const Vec3 b = surface.points.col(surface.triangles(1, t));
    const Vec3 c = surface.points.col(surface.triangles(2, t));
    const Real longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!((b - a).cross(c - a).norm() > kDegenerateArea * longest * longest))
      throw InputError(fmt::format("{}: triangle {} (points {} {} {}) has zero area", what, t,
                                   surface.triangles(0, t), surface.triangles(1, t),
                                   surface.triangles(2, t)));
  }
}

// Whether each component is closed: none of its edges on a rim.
std::vector<char> closed_components(const Components& components, const Adjacency& adjacency) {
  std::vector<char> closed(components.first.size(), 1);
  for (size_t s = 0; s < adjacency.neighbour.size(); ++s)
    if (adjacency.neighbour[s] < 0) closed[static_cast<size_t>(components.of[s / 3])] = 0;
  return closed;
}

// Six times the signed volume each component encloses (meaningful for closed ones).
std::vector<Real> enclosed_volumes(const Points& points, const Triangles& triangles,
                                   const Components& components) {
  std::vector<Real> volume(components.first.size(), 0.0);
  for (Index t = 0; t < triangles.cols(); ++t) {
    const size_t c = static_cast<size_t>(components.of[static_cast<size_t>(t)]);
    // Relative to a point of the component, for accuracy far from the origin.
    const Vec3 o = points.col(triangles(0, components.first[c]));
    const Vec3 a = points.col(triangles(0, t)) - o;
    const Vec3 b = points.col(triangles(1, t)) - o;
    const Vec3 d = points.col(triangles(2, t)) - o;
    volume[c] += a.dot(b.cross(d));
  }
  return volume;
}

}  // namespace

ObstaclePtr make_meshed_surface(const mesh::RigidSurface& surface,
                                const Eigen::Matrix<Real, 3, Eigen::Dynamic>& body_points,
                                const std::string& where) {
  const std::string what = fmt::format("{}: the rigid surface '{}'", where, surface.name);
  require_valid_input(surface, what);
  Triangles triangles = surface.triangles;
  const Adjacency adjacency = edge_adjacency(triangles, what);
  require_manifold_vertices(triangles, adjacency, surface.points.cols(), what);
  const Components components = orient_consistently(triangles, adjacency, what);
  // Flipping triangles keeps which triangles share an edge and which are on a rim: the components
  // and the rims of `adjacency` still hold (not its slots' edge numbers).
  const std::vector<char> closed = closed_components(components, adjacency);
  const std::vector<Real> volume = enclosed_volumes(surface.points, triangles, components);
  std::vector<char> flip(closed.size(), 0);
  for (size_t c = 0; c < closed.size(); ++c)
    flip[c] = closed[c] && volume[c] < 0.0 ? 1 : 0;
  flip_components(triangles, components, flip);
  auto obstacle = std::make_shared<MeshedSurface>(surface.points, std::move(triangles));

  // Each open component faces the side where most of the body points nearest to it lie.
  if (std::find(closed.begin(), closed.end(), 0) == closed.end()) return obstacle;
  std::vector<Index> votes(closed.size(), 0);
  for (Index p = 0; p < body_points.cols(); ++p) {
    const Vec3 x = body_points.col(p);
    const Nearest n = obstacle->nearest(x);
    if (std::sqrt(n.squared_distance) <= obstacle->on_surface()) continue;
    const Real side = obstacle->side(x, n);
    votes[static_cast<size_t>(components.of[static_cast<size_t>(n.triangle)])] +=
        side > 0.0 ? 1 : (side < 0.0 ? -1 : 0);
  }
  for (size_t c = 0; c < closed.size(); ++c)
    flip[c] = !closed[c] && votes[c] < 0 ? 1 : 0;
  if (std::find(flip.begin(), flip.end(), 1) != flip.end()) obstacle->flip(components, flip);
  return obstacle;
}

std::pair<Eigen::Matrix<Real, 3, Eigen::Dynamic>, Eigen::Matrix<Index, 3, Eigen::Dynamic>>
oriented_triangles(const Obstacle& obstacle) {
  if (const auto* surface = dynamic_cast<const MeshedSurface*>(&obstacle))
    return {surface->points(), surface->triangles()};
  return {};
}

}  // namespace fricon::contact
