#pragma once
// Where each error state sits in the local EKF's 22-vector (local_ekf.hpp's file comment).
namespace scantling::localization::detail {

inline constexpr int kP = 0;        // δp, odom, m
inline constexpr int kTheta = 3;    // δθ, odom (left), rad
inline constexpr int kV = 6;        // δv, odom, m/s
inline constexpr int kBa = 9;       // δb_a, body, m/s²
inline constexpr int kBg = 12;      // δb_g, body, rad/s
inline constexpr int kBaro = 15;    // δb_baro, m
inline constexpr int kCloneP = 16;  // δp₀ of the clone
inline constexpr int kCloneTheta = 19;
inline constexpr int kCoreDim = 16;  // all but the clone: what the IMU propagates

}  // namespace scantling::localization::detail
