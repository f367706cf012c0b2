// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Basic value types shared by every stage of the engine.
#include <Eigen/Core>
#include <cstdint>

namespace dda {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat26 = Eigen::Matrix<double, 2, 6>;
using VecX = Eigen::VectorXd;

// Blocks, contacts, loads and monitors are referred to by index, never by
// pointer: the arrays behind them grow and pointers would go stale.
using BlockId = std::int32_t;

constexpr double kPi = 3.14159265358979323846;
inline double deg_to_rad(double deg) { return deg * kPi / 180.0; }

}  // namespace dda
