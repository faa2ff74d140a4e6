#pragma once
// core: the scalar and index types, and the small fixed-size vectors every stage shares.
// Depends on nothing of ours. Reals are double (no templating on the scalar); indices are signed.

#include <Eigen/Dense>

namespace fricon {

using Index = Eigen::Index;
using Real = double;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VectorXd = Eigen::VectorXd;
using MatrixXd = Eigen::MatrixXd;

}  // namespace fricon

#include <cstdint>

#include <Eigen/SparseCore>

namespace fricon {

/// Index type of sparse matrices: 64-bit, so that factors of million-unknown meshes fit.
using SparseIndex = std::int64_t;
/// Compressed-column sparse matrix used for K and B.
using SparseMatrix = Eigen::SparseMatrix<Real, Eigen::ColMajor, SparseIndex>;

}  // namespace fricon
