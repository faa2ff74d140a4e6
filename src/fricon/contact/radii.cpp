#include "fricon/contact/radii.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fricon/core/error.hpp"

namespace fricon::contact {

namespace {

struct PolyVertex {
  Vec3 x;
  Real phi, g;
};

// Clips a convex polygon to {phi >= s} (keep_above) or {phi <= s}, interpolating linearly.
std::vector<PolyVertex> clip(const std::vector<PolyVertex>& poly, Real s, bool keep_above) {
  std::vector<PolyVertex> out;
  auto inside = [&](const PolyVertex& v) { return keep_above ? v.phi >= s : v.phi <= s; };
  for (size_t i = 0; i < poly.size(); ++i) {
    const PolyVertex& a = poly[i];
    const PolyVertex& b = poly[(i + 1) % poly.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const Real w = (s - a.phi) / (b.phi - a.phi);
      out.push_back({a.x + w * (b.x - a.x), s, a.g + w * (b.g - a.g)});
    }
  }
  return out;
}

// Integral of F(phi) g over a triangle where F is smooth (linear for the built-in laws):
// the 3-point edge-midpoint rule is exact for quadratics (F linear times g linear).
Real integrate_piece(const PolyVertex& a, const PolyVertex& b, const PolyVertex& c,
                     const FrictionLaw& F) {
  const Real area = 0.5 * (b.x - a.x).cross(c.x - a.x).norm();
  Real sum = 0.0;
  const PolyVertex* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const PolyVertex& p = *v[e];
    const PolyVertex& q = *v[(e + 1) % 3];
    sum += F(0.5 * (p.phi + q.phi)) * 0.5 * (p.g + q.g);
  }
  return area * sum / 3.0;
}

}  // namespace

VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g) {
  FRICON_CHECK(phi.size() == surface.n_nodes() && g.size() == surface.n_nodes(),
               "phi and g need one value per surface node");
  const std::vector<Real> kinks = F.kinks();
  VectorXd rho = VectorXd::Zero(patches.size());
  for (Index p = 0; p < patches.size(); ++p) {
    Real integral = 0.0;
    for (Index k : patches.faces[static_cast<size_t>(p)]) {
      std::vector<PolyVertex> tri(3);
      Real lo = INFINITY, hi = -INFINITY;
      for (int v = 0; v < 3; ++v) {
        const Index s = surface.face_nodes(v, k);
        tri[v] = {mesh.nodes.col(surface.nodes[static_cast<size_t>(s)]), phi(s), g(s)};
        lo = std::min(lo, phi(s));
        hi = std::max(hi, phi(s));
      }
      // Slabs between consecutive kinks that cut the triangle.
      std::vector<Real> cuts{lo};
      for (Real t : kinks)
        if (t > lo && t < hi) cuts.push_back(t);
      cuts.push_back(hi);
      for (size_t c = 0; c + 1 < cuts.size(); ++c) {
        std::vector<PolyVertex> piece = tri;
        if (c > 0) piece = clip(piece, cuts[c], true);
        if (c + 2 < cuts.size()) piece = clip(piece, cuts[c + 1], false);
        for (size_t i = 1; i + 1 < piece.size(); ++i)
          integral += integrate_piece(piece[0], piece[i], piece[i + 1], F);
      }
    }
    rho(p) = integral / patches.area(p);
  }
  return rho;
}

}  // namespace fricon::contact
