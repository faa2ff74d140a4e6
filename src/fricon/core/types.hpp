#pragma once
// core: the scalar and index types, and the small fixed-size vectors every stage shares.
// Depends on nothing of ours. Reals are double (no templating on the scalar); indices are signed.

#include <Eigen/Core>

namespace fricon {

using Index = Eigen::Index;
using Real = double;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VectorXd = Eigen::VectorXd;
using MatrixXd = Eigen::MatrixXd;

}  // namespace fricon
