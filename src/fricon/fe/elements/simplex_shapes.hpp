#pragma once
// fe/elements: the Lagrange shape functions of a simplex in barycentric coordinates lambda_0..
// lambda_dim, shared by the tetrahedra and the triangles (theory.md §2.12). Linear: lambda_a.
// Quadratic: lambda_a (2 lambda_a - 1) at the corners, 4 lambda_a lambda_b on the edges, in the
// order of the element's edge table (mesh::kTetEdge, mesh::kTriangleEdge). Derivatives are along
// the reference coordinates xi_i = lambda_i (i = 1..dim), so d/dxi_i = d/dlambda_i - d/dlambda_0.

#include "fricon/fe/element.hpp"

namespace fricon::fe::simplex {

/// Derivatives of the linear functions (constant): row 0 all -1, then the identity.
inline ShapeDerivatives linear_derivatives(int dim) {
  ShapeDerivatives d = ShapeDerivatives::Zero(dim + 1, dim);
  d.row(0).setConstant(-1.0);
  d.bottomRows(dim).setIdentity();
  return d;
}

/// The reference points of the quadratic nodes of a simplex with `corners` corners: the
/// corners, then the edges' midpoints.
template <int Edges>
MatrixXd quadratic_node_points(int corners, const int (&edge)[Edges][2]) {
  MatrixXd p = MatrixXd::Zero(corners, corners + Edges);
  p.leftCols(corners).setIdentity();
  for (int e = 0; e < Edges; ++e) {
    p(edge[e][0], corners + e) = 0.5;
    p(edge[e][1], corners + e) = 0.5;
  }
  return p;
}

template <int Edges>
ShapeValues quadratic_values(const VectorXd& l, const int (&edge)[Edges][2]) {
  const Index corners = l.size();
  ShapeValues N(corners + Edges);
  for (Index a = 0; a < corners; ++a)
    N(a) = l(a) * (2.0 * l(a) - 1.0);
  for (int e = 0; e < Edges; ++e)
    N(corners + e) = 4.0 * l(edge[e][0]) * l(edge[e][1]);
  return N;
}

template <int Edges>
ShapeDerivatives quadratic_derivatives(const VectorXd& l, const int (&edge)[Edges][2]) {
  const Index corners = l.size();
  MatrixXd dl = MatrixXd::Zero(corners + Edges, corners);  // along lambda_0..lambda_dim
  for (Index a = 0; a < corners; ++a)
    dl(a, a) = 4.0 * l(a) - 1.0;
  for (int e = 0; e < Edges; ++e) {
    const int a = edge[e][0], b = edge[e][1];
    dl(corners + e, a) = 4.0 * l(b);
    dl(corners + e, b) = 4.0 * l(a);
  }
  ShapeDerivatives d(corners + Edges, corners - 1);
  for (Index i = 1; i < corners; ++i)
    d.col(i - 1) = dl.col(i) - dl.col(0);
  return d;
}

}  // namespace fricon::fe::simplex
