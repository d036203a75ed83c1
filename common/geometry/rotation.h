#pragma once
// Rotations in 3D, exact at the thesis's degenerate cases (Eq. 8 and its uses in Eq. 15).
//
// Theta (thesis Eq. 8) is Rodrigues' formula: the rotation by `angle` (radians,
// right-handed) about the unit axis n = axis / |axis|,
//   R = I + sin(angle) [n]x + (1 - cos(angle)) [n]x^2,
// evaluated with 1 - cos(angle) = 2 sin^2(angle / 2), which keeps full relative precision at
// tiny angles (at 1e-9 rad, 1 - cos rounds to 0 in double while 2 sin^2 gives 5e-19), so no
// series expansion is needed for Theta. The rotation-vector form (ExpSo3) uses the Taylor
// series of sin(t)/t and (1 - cos t)/t^2 below 1e-4 rad, where they are exact to rounding.
//
// Eq. 8 as printed, R = Theta(v* x v_n, acos(v* . v_n / (|v*| |v_n|))), is RotationBetween(v*,
// v_n), which stays defined where the printed form breaks (v* x v_n = 0, rounded acos).
//
// Angles between vectors use atan2(|u x v|, u . v) instead of acos of the normalised dot
// product: acos is ill-conditioned near 0 and pi and undefined when rounding pushes the dot
// product just above 1 or below -1.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace reenact {

// Skew-symmetric matrix [v]x with [v]x w = v x w.
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);

// Rodrigues (Eq. 8): rotation by `angle` (radians) about `axis` (any length > 0; it is
// normalised). nullopt if the axis is zero or any input is not finite.
std::optional<Eigen::Matrix3d> Theta(const Eigen::Vector3d& axis, double angle);

// Rotation whose axis is omega / |omega| and whose angle is |omega| (radians): the
// exponential map of so(3). Identity for omega = 0. Precondition (CHECK): omega finite.
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& omega);

// Angle in [0, pi] between two directions, via atan2. nullopt if either vector is zero or
// not finite.
std::optional<double> AngleBetween(const Eigen::Vector3d& u, const Eigen::Vector3d& v);

// The minimal rotation R (smallest angle) with R u/|u| = v/|v|; its axis is u x v. Defined
// for every pair of non-zero finite vectors:
//  - parallel (u x v = 0, u . v > 0): identity;
//  - anti-parallel (angle pi): rotation by pi about a deterministic unit axis perpendicular
//    to u: u x e_k normalised, e_k the coordinate axis of u's smallest-magnitude component
//    (the first such one on ties);
//  - nearly anti-parallel: the axis is u x v with its component along u projected out, so
//    that rounding in the cross product cannot tilt it.
// nullopt if either vector is zero or not finite.
std::optional<Eigen::Matrix3d> RotationBetween(const Eigen::Vector3d& u, const Eigen::Vector3d& v);

// A deterministic unit vector perpendicular to u (as described for RotationBetween).
// nullopt if u is zero or not finite.
std::optional<Eigen::Vector3d> AnyPerpendicular(const Eigen::Vector3d& u);

// Rotation angle in [0, pi] of a rotation matrix, via atan2(|vee(R - R^T)| / 2,
// (trace R - 1) / 2): accurate at both small angles and near pi. Precondition: R orthonormal
// with det +1 (not checked; for other matrices the value is that of the formula).
double RotationAngle(const Eigen::Matrix3d& r);

// max |(R^T R - I)_ij|: how far a matrix is from orthonormal.
double OrthonormalityError(const Eigen::Matrix3d& r);

// The rotation nearest to m in the Frobenius norm (SVD projection onto SO(3), with the
// determinant corrected to +1). Precondition (CHECK): m finite.
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& m);

}  // namespace reenact
