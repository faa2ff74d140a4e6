#include "fricon/contact/radii.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "fricon/contact/surface_integrals.hpp"
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

// Exact radii for a piecewise-linear F (theory.md §2.6, "exact integration").
VectorXd exact_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g) {
  const std::vector<Real> kinks = F.kinks();
  VectorXd rho = VectorXd::Zero(patches.size());
  for (Index p = 0; p < patches.size(); ++p) {
    Real integral = 0.0;
    for (Index k : patches.faces[static_cast<size_t>(p)])
      for (const std::array<Index, 3>& nodes : linear_pieces(mesh, surface, k)) {
        std::vector<PolyVertex> tri(3);
        Real lo = INFINITY, hi = -INFINITY;
        for (int v = 0; v < 3; ++v) {
          const Index s = nodes[static_cast<size_t>(v)];
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

// ---------------------------------------------------------------------------------------------
// Adaptive Gauss-Kronrod on the level-line reduction (theory.md §2.6, "laws that are not
// piecewise linear").

// Gauss-Kronrod 7-15 on [-1, 1]: the Kronrod abscissae x_j (the last is 0) and weights, and the
// weights of the 7-point Gauss rule on the abscissae x_1, x_3, x_5 (and their negatives) and 0.
constexpr std::array<Real, 8> kKronrodX = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr std::array<Real, 8> kKronrodW = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<Real, 4> kGaussW = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
constexpr int kNodesPerInterval = 15;

// Rounds of bisection before the quadrature gives up (each halves the failing intervals; 60
// halvings take any interval below the resolution of a double).
constexpr int kMaxQuadratureRounds = 60;

// At most this many intervals at once: kMaxIntervalsFactor x the initial ones + kMaxIntervalsExtra
// (bounds the memory, 15 nodes of 16 bytes each per interval).
constexpr size_t kMaxIntervalsFactor = 16;
constexpr size_t kMaxIntervalsExtra = 100000;

// A triangle whose range of phi_h is below this fraction of |phi_h| is treated as having a
// constant phi_h (the level-line weight would divide by ~0).
constexpr Real kFlatRelative = 1e-13;

// A piece of the 1D integral int F(s) w(s) ds (theory.md §2.6, eq. (2.6.2)): s = base + sign u
// for u in [lo, hi], and w = c1 u + c2 u^2 there.
struct Interval {
  Index patch;
  Real base, sign;
  Real c1, c2;
  Real lo, hi;
};

// The intervals of one triangle's sub-range, u in [0, length] from `base` in direction `sign`,
// split at the kinks strictly inside.
void push_pieces(Index patch, Real base, Real sign, Real c1, Real c2, Real length,
                 const std::vector<Real>& kinks, std::vector<Interval>& out) {
  std::vector<Real> cuts{0.0};
  for (Real t : kinks) {
    const Real u = sign * (t - base);
    if (u > 0.0 && u < length) cuts.push_back(u);
  }
  cuts.push_back(length);
  std::sort(cuts.begin(), cuts.end());
  for (size_t c = 0; c + 1 < cuts.size(); ++c)
    out.push_back({patch, base, sign, c1, c2, cuts[c], cuts[c + 1]});
}

// The level-line reduction of every triangle of the patches (theory.md §2.6, eq. (2.6.2)):
// intervals of the 1D integrals, and for triangles with a constant phi_h point values
// weight * F(s).
struct Reduction {
  std::vector<Interval> intervals;
  std::vector<Real> flat_s, flat_weight;
  std::vector<Index> flat_patch;
  std::vector<Real> length;  // total length of the intervals of each patch [m]
};

Reduction level_line_reduction(const mesh::TetMesh& mesh, const ContactSurface& surface,
                               const Patches& patches, const std::vector<Real>& kinks,
                               const VectorXd& phi, const VectorXd& g) {
  Reduction r;
  r.length.assign(static_cast<size_t>(patches.size()), 0.0);
  for (Index p = 0; p < patches.size(); ++p) {
    for (Index k : patches.faces[static_cast<size_t>(p)])
      for (const std::array<Index, 3>& nodes : linear_pieces(mesh, surface, k)) {
        std::array<Index, 3> v = nodes;
        std::array<Vec3, 3> x;
        for (int i = 0; i < 3; ++i) {
          x[i] = mesh.nodes.col(surface.nodes[static_cast<size_t>(v[i])]);
        }
        const Real A = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
        std::sort(v.begin(), v.end(), [&](Index a, Index b) { return phi(a) < phi(b); });
        const Real s0 = phi(v[0]), s1 = phi(v[1]), s2 = phi(v[2]);
        const Real g0 = g(v[0]), g1 = g(v[1]), g2 = g(v[2]);
        if (s2 - s0 <= kFlatRelative * std::max(std::abs(s0), std::abs(s2))) {
          r.flat_s.push_back(0.5 * (s0 + s2));
          r.flat_weight.push_back(A * (g0 + g1 + g2) / 3.0);
          r.flat_patch.push_back(p);
          continue;
        }
        r.length[static_cast<size_t>(p)] += s2 - s0;
        const Real d1 = s1 - s0, e1 = s2 - s1, d = s2 - s0;
        if (d1 > 0.0)  // lower part, u = s - s0 in [0, d1]
          push_pieces(p, s0, 1.0, 2.0 * A * g0 / (d1 * d),
                      A * ((g1 - g0) / d1 + (g2 - g0) / d) / (d1 * d), d1, kinks, r.intervals);
        if (e1 > 0.0)  // upper part, u = s2 - s in [0, e1]
          push_pieces(p, s2, -1.0, 2.0 * A * g2 / (e1 * d),
                      A * ((g1 - g2) / e1 + (g0 - g2) / d) / (e1 * d), e1, kinks, r.intervals);
      }
  }
  return r;
}

// The 15 Kronrod nodes s of each interval, after n_flat leading entries, into t.
void kronrod_nodes(const std::vector<Interval>& intervals, size_t n_flat, std::vector<Real>& t) {
  for (size_t i = 0; i < intervals.size(); ++i) {
    const Interval& I = intervals[i];
    const Real mid = 0.5 * (I.lo + I.hi), half = 0.5 * (I.hi - I.lo);
    Real* ti = t.data() + n_flat + kNodesPerInterval * i;
    for (int j = 0; j < 7; ++j) {
      ti[2 * j] = I.base + I.sign * (mid - half * kKronrodX[j]);
      ti[2 * j + 1] = I.base + I.sign * (mid + half * kKronrodX[j]);
    }
    ti[14] = I.base + I.sign * mid;
  }
}

// One interval's Kronrod-15 value, |K15 - G7| error estimate and integral of |F w|, from F at
// its nodes (fi, in kronrod_nodes' order).
struct Estimate {
  Real value, error, magnitude;
};

Estimate gauss_kronrod(const Interval& I, const Real* fi) {
  const Real mid = 0.5 * (I.lo + I.hi), half = 0.5 * (I.hi - I.lo);
  auto integrand = [&](Real fv, Real u) { return fv * (I.c1 * u + I.c2 * u * u); };
  Real K = 0.0, G = 0.0, M = 0.0;
  for (int j = 0; j < 7; ++j) {
    const Real a = integrand(fi[2 * j], mid - half * kKronrodX[j]);
    const Real b = integrand(fi[2 * j + 1], mid + half * kKronrodX[j]);
    K += kKronrodW[j] * (a + b);
    M += kKronrodW[j] * (std::abs(a) + std::abs(b));
    if (j % 2 == 1) G += kGaussW[j / 2] * (a + b);
  }
  const Real c = integrand(fi[14], mid);
  K += kKronrodW[7] * c;
  M += kKronrodW[7] * std::abs(c);
  G += kGaussW[3] * c;
  return {half * K, half * std::abs(K - G), half * M};
}

VectorXd quadrature_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                          const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                          const VectorXd& g) {
  const Real rtol = F.quadrature_rtol();
  FRICON_CHECK(rtol > 0.0 && rtol < 1.0, "quadrature_rtol = " << rtol << " is not in (0, 1)");
  const auto n_patches = static_cast<size_t>(patches.size());
  Reduction red = level_line_reduction(mesh, surface, patches, F.kinks(), phi, g);
  std::vector<Interval>& active = red.intervals;

  // The accepted parts of each patch's integral [N], of its integral of |F g_h| and of its
  // estimated error.
  std::vector<Real> integral(n_patches, 0.0), scale(n_patches, 0.0), accepted_error(n_patches, 0.0);
  const size_t max_intervals = kMaxIntervalsFactor * active.size() + kMaxIntervalsExtra;
  std::vector<Real> t, f;
  for (int round = 0; !active.empty() || round == 0; ++round) {
    if (round == kMaxQuadratureRounds)
      throw NumericalError(fmt::format(
          "the quadrature of the radii did not reach quadrature_rtol = {} in {} rounds of "
          "bisection for the friction law {} ({} intervals left): F may be discontinuous or "
          "have kinks not listed in contact.friction.kinks",
          rtol, kMaxQuadratureRounds, F.describe(), active.size()));
    // All nodes of all intervals (and, in the first round, the flat triangles) in one batch.
    const size_t n_flat = round == 0 ? red.flat_s.size() : 0;
    t.assign(n_flat + kNodesPerInterval * active.size(), 0.0);
    std::copy(red.flat_s.begin(), red.flat_s.begin() + static_cast<std::ptrdiff_t>(n_flat),
              t.begin());
    kronrod_nodes(active, n_flat, t);
    f.assign(t.size(), 0.0);
    F.evaluate(t, f);
    for (size_t i = 0; i < n_flat; ++i) {
      const auto p = static_cast<size_t>(red.flat_patch[i]);
      integral[p] += red.flat_weight[i] * f[i];
      scale[p] += std::abs(red.flat_weight[i] * f[i]);
    }
    std::vector<Estimate> estimate(active.size());
    std::vector<Real> trial_scale = scale, trial_error = accepted_error;
    for (size_t i = 0; i < active.size(); ++i) {
      estimate[i] = gauss_kronrod(active[i], f.data() + n_flat + kNodesPerInterval * i);
      trial_scale[static_cast<size_t>(active[i].patch)] += estimate[i].magnitude;
      trial_error[static_cast<size_t>(active[i].patch)] += estimate[i].error;
    }

    // A patch whose estimated error (accepted intervals and these) is within rtol x its scale
    // is done. Otherwise an interval is accepted when its error is within half its share of
    // rtol x the patch's scale, shared by the interval's own magnitude or by its length (the
    // sum of either share is <= rtol x scale, so the accepted errors stay within it); the
    // others are bisected.
    std::vector<Interval> next;
    for (size_t i = 0; i < active.size(); ++i) {
      const Interval& I = active[i];
      const Estimate& e = estimate[i];
      const auto p = static_cast<size_t>(I.patch);
      const Real share =
          std::max(e.magnitude, trial_scale[p] * (I.hi - I.lo) / std::max(red.length[p], 1e-300));
      if (trial_error[p] <= rtol * trial_scale[p] || e.error <= 0.5 * rtol * share) {
        integral[p] += e.value;
        scale[p] += e.magnitude;
        accepted_error[p] += e.error;
      } else {
        const Real mid = 0.5 * (I.lo + I.hi);
        next.push_back({I.patch, I.base, I.sign, I.c1, I.c2, I.lo, mid});
        next.push_back({I.patch, I.base, I.sign, I.c1, I.c2, mid, I.hi});
      }
    }
    if (next.size() > max_intervals)
      throw NumericalError(fmt::format(
          "the quadrature of the radii did not reach quadrature_rtol = {} for the friction law "
          "{}: {} intervals would be needed (at most {}); F may oscillate too fast, or the "
          "tolerance be too tight",
          rtol, F.describe(), next.size(), max_intervals));
    active = std::move(next);
  }

  VectorXd rho(patches.size());
  for (Index p = 0; p < patches.size(); ++p)
    rho(p) = integral[static_cast<size_t>(p)] / patches.area(p);
  return rho;
}

}  // namespace

std::string radius_integration(const FrictionLaw& F) {
  if (F.piecewise_linear()) return kRadiusIntegration;
  return fmt::format(
      "adaptive Gauss-Kronrod (7-15) on the level-line reduction, rtol {}, split at kinks "
      "({} given)",
      F.quadrature_rtol(), F.kinks().size());
}

VectorXd patch_radii(const mesh::TetMesh& mesh, const ContactSurface& surface,
                     const Patches& patches, const FrictionLaw& F, const VectorXd& phi,
                     const VectorXd& g) {
  FRICON_CHECK(phi.size() == surface.n_nodes() && g.size() == surface.n_nodes(),
               "phi and g need one value per surface node");
  if (F.piecewise_linear()) return exact_radii(mesh, surface, patches, F, phi, g);
  return quadrature_radii(mesh, surface, patches, F, phi, g);
}

}  // namespace fricon::contact
