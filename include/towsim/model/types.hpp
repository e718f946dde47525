// The vector and matrix types of the physics library (Eigen, double).
#pragma once

#include <Eigen/Dense>

namespace towsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Quat = Eigen::Quaterniond;

}  // namespace towsim
