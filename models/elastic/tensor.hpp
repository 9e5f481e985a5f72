// Eigen views of the row-major 3x3 tensors stored per particle.
#pragma once
#include <Eigen/Dense>
#include <petscsys.h>

namespace burst {
using Mat3     = Eigen::Matrix<PetscReal, 3, 3, Eigen::RowMajor>;
using Mat3Map  = Eigen::Map<Mat3>;
using Mat3CMap = Eigen::Map<const Mat3>;
} // namespace burst
