#pragma once
// fe: the finite element, a Lagrange element on a simplex (theory.md §2.1, §2.12): its shape
// functions on the reference cell, their derivatives, and the quadrature rules that integrate
// its stiffness and mass exactly on straight-sided cells. The element of a mesh is chosen once
// from the mesh's order (elements_of); assembly, loads, stresses and the contact integrals read
// n_nodes() and the tabulated rules, never a literal node count. One element per file in
// fe/elements/ (deal.II's FiniteElement and MFEM's FiniteElementCollection are the models).

#include <string_view>
#include <vector>

#include "fricon/core/types.hpp"
#include "fricon/fe/quadrature.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

/// The most nodes of any element (the 10-node tetrahedron): element matrices have this capacity
/// on the stack instead of allocating per element.
inline constexpr int kMaxElementNodes = 10;
inline constexpr int kMaxElementDofs = 3 * kMaxElementNodes;

/// Shape function values at one point (one per node).
using ShapeValues = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxElementNodes, 1>;
/// Shape function derivatives at one point: row a is node a's, column i the derivative along
/// reference coordinate i (on the reference cell, or along x, y, z after mapping).
using ShapeDerivatives =
    Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxElementNodes, 3>;
/// Coordinates [m] of an element's nodes, one column per node, in the element's node order.
using ElementNodes = Eigen::Matrix<Real, 3, Eigen::Dynamic, 0, 3, kMaxElementNodes>;
/// An element matrix over the element's dofs (3 per node, node-major) [N/m].
using ElementMatrix =
    Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxElementDofs, kMaxElementDofs>;
using ElementVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxElementDofs, 1>;

/// The shape functions of an element at the points of a quadrature rule, computed once.
struct Tabulation {
  QuadratureRule rule;           ///< barycentric points, weights as fractions of the cell
  Real reference_measure = 0.0;  ///< measure of the reference cell: 1/6 or 1/2
  std::vector<ShapeValues> values;
  std::vector<ShapeDerivatives> derivatives;  ///< along the reference coordinates
  Index size() const { return rule.weights.size(); }
  /// Weight of point q on the reference cell: rule.weights(q) * reference_measure.
  Real weight(Index q) const { return rule.weights(q) * reference_measure; }
};

/// A Lagrange element on the reference simplex of dimension dim() (3: the tetrahedron with
/// corners 0, e1, e2, e3; 2: the triangle 0, e1, e2). Points are given in barycentric
/// coordinates (dim() + 1 entries summing to 1); the reference coordinate i (1 <= i <= dim) is
/// the barycentric coordinate i. Nodes are numbered as Gmsh numbers them (corners first).
class Element {
 public:
  virtual ~Element() = default;
  virtual std::string_view name() const = 0;
  virtual int dim() const = 0;
  virtual int order() const = 0;
  virtual int n_nodes() const = 0;
  /// The nodes' reference points, barycentric, one column per node.
  virtual MatrixXd node_points() const = 0;
  /// The shape functions at barycentric point `bary`.
  virtual ShapeValues values(const VectorXd& bary) const = 0;
  /// Their derivatives along the reference coordinates at `bary` (n_nodes x dim).
  virtual ShapeDerivatives derivatives(const VectorXd& bary) const = 0;
  /// Points that integrate the stiffness exactly on a straight-sided cell (degree 2 (order-1),
  /// at least one point) and the mass exactly (degree 2 order), with the shape functions there.
  virtual const Tabulation& stiffness_points() const = 0;
  virtual const Tabulation& mass_points() const = 0;
  /// The element cut into linear simplices through its nodes, one column of dim() + 1 local
  /// node indices each: the element itself at order 1, the four corner-and-midpoint triangles
  /// of a 6-node triangle (where a piecewise-linear view of a field is needed, theory.md §2.12).
  virtual Eigen::MatrixXi linear_pieces() const = 0;

 protected:
  /// The shape functions at the points of `rule`, on a cell of measure `reference_measure`.
  Tabulation tabulate(const QuadratureRule& rule, Real reference_measure) const;
};

/// The elements of one order (MFEM's collection): on the tetrahedra and on their boundary
/// triangles (the traces).
struct ElementFamily {
  const Element& cell;
  const Element& face;
  int order() const { return cell.order(); }
};

/// The Lagrange elements of order 1 (4-node tetrahedron, 3-node triangle) or 2 (10 and 6 nodes).
/// Throws InputError for another order.
const ElementFamily& lagrange_elements(int order);

/// The elements of the mesh's order (mesh::TetMesh::order).
inline const ElementFamily& elements_of(const mesh::TetMesh& mesh) {
  return lagrange_elements(mesh.order());
}

/// The coordinates of every node of tetrahedron t and of boundary triangle f.
ElementNodes tet_points(const mesh::TetMesh& mesh, Index t);
ElementNodes face_points(const mesh::TetMesh& mesh, Index f);

/// The map of a cell at one point: J = x dN (3 x 3), its determinant, and the shape functions'
/// gradients along x, y, z (n_nodes x 3). det <= 0 means an inverted or badly curved cell.
struct CellMap {
  Real det = 0.0;
  ShapeDerivatives grad;
};
CellMap map_cell(const ElementNodes& x, const ShapeDerivatives& dN);

/// The map of a surface triangle at one point: the area element |x_xi1 x x_xi2| (the measure
/// of the reference triangle's dS) and the unit normal, right-handed in the node order.
struct FaceMap {
  Real area_element = 0.0;
  Vec3 normal = Vec3::Zero();
};
FaceMap map_face(const ElementNodes& x, const ShapeDerivatives& dN);

/// Checks every tetrahedron's map: det J > 0 at the stiffness points and at the corners,
/// relative to the straight cell through the corners (above `min_ratio` times 6 |corner
/// tetrahedron|). Throws InputError naming `source`, the tetrahedron and its nodes when it is
/// inverted or so badly curved that its Jacobian changes sign.
void check_jacobians(const mesh::TetMesh& mesh, const std::string& source, Real min_ratio = 1e-6);

}  // namespace fricon::fe
