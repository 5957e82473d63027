// Bodies: design pose, inertia (in body coordinates), shapes (compile_shapes.cpp).
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <cmath>

#include "model/compiler.hpp"

namespace mechkin {

void Compiler::CompileBody(const BodySpec& b) {
  Body body;
  const auto& name = b.name;
  // In a file placed by markers a body without a position is placed by compile.
  const bool sketched = b.position.has_value();
  auto pos = !sketched && by_markers_ ? std::optional<Vec3>(Vec3::Zero()) : LengthVector(b.position);
  body.euler = Vec4(1, 0, 0, 0);
  bool ok = name && pos;
  if (b.orientation) {
    auto q = CompileOrientation(*b.orientation);
    if (q)
      body.euler = *q;
    else
      ok = false;
  }
  if (name && *name == "ground") {
    Error(b.pointer + "/name", "'ground' is reserved for the fixed frame and cannot be a moving body",
          "rename the body, or attach parts to ground directly");
    ok = false;
  } else if (name && body_index_.count(*name)) {
    Error(b.pointer + "/name", "duplicate body name '" + *name + "'", "give every body a unique name");
    ok = false;
  }
  if (!ok) {
    if (name && *name != "ground") body_index_.emplace(*name, -2);  // known name, invalid body
    return;
  }
  body.name = *name;
  body.position = *pos;
  if (b.shape) body.shape = CompileShape(*b.shape);
  body.shapes = CompileShapes(b.shapes);
  if (b.inertia) {
    body.inertia = CompileInertia(*b.inertia, *pos, body.euler);
    if (!body.inertia) {
      body_index_.emplace(*name, -2);
      return;
    }
  }
  body_index_[body.name] = static_cast<BodyIndex>(model_.bodies.size());
  model_.bodies.push_back(body);
  sketched_.push_back(sketched);
  CompileMarkers(body_index_[body.name], b.markers);
}

// Orientation forms (format-v1 "orientation"); angles in the file's unit.
std::optional<Vec4> Compiler::CompileOrientation(const OrientationSpec& o) {
  if (!o.ok) return std::nullopt;
  if (o.form == OrientationSpec::Form::AxisAngle) {
    auto axis = VectorValue(o.axis, true);
    auto angle = Value(o.angle);
    if (!axis || !angle) return std::nullopt;
    return QuatFromAxisAngle(axis->normalized(), *angle * angle_);
  }
  if (o.form == OrientationSpec::Form::Matrix) return CompileRotationMatrix(o);
  const std::string p = o.pointer + "/euler_parameters";
  Vec4 q;
  for (int k = 0; k < 4; ++k) {
    const auto c = Value(o.euler[k]);
    if (!c) return std::nullopt;
    q[k] = *c;
  }
  if (!(q.norm() > 1e-12) || !std::isfinite(q.norm())) {
    Error(p, "Euler parameters have (almost) zero length", "give a unit quaternion, e.g. [1, 0, 0, 0]");
    return std::nullopt;
  }
  if (std::abs(q.norm() - 1) > 1e-6) Warn(p, "Euler parameters are not unit length; normalised");
  return q.normalized();
}

// Re-orthonormalises small CAD round-off silently, larger defects with a warning,
// and rejects matrices that are not rotations at all.
std::optional<Vec4> Compiler::CompileRotationMatrix(const OrientationSpec& o) {
  const std::string p = o.pointer + "/matrix";
  Mat3 R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto c = Value(o.matrix[i][j]);
      if (!c) return std::nullopt;
      R(i, j) = *c;
    }
  const double defect = (R.transpose() * R - Mat3::Identity()).norm();
  if (!(defect <= 1e-2) || !(R.determinant() > 0)) {
    Error(p,
          "matrix is not a rotation (orthonormality defect " + std::to_string(defect) +
              (R.determinant() > 0 ? "" : ", determinant <= 0") + ")",
          "give a proper orthonormal matrix (columns = body axes in global components)");
    return std::nullopt;
  }
  if (defect > 1e-9)
    Warn(p, "matrix is not exactly orthonormal (defect " + std::to_string(defect) + "); re-orthonormalised");
  Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return QuatFromMatrix(svd.matrixU() * svd.matrixV().transpose());
}

// Stored in body coordinates: s'_c = Aᵀ(c − r), J' = Aᵀ J A.
std::optional<Inertia> Compiler::CompileInertia(const InertiaSpec& in, const Vec3& r, const Vec4& euler) {
  if (!in.ok) return std::nullopt;
  const std::string& ptr = in.pointer;
  Inertia out;
  auto mass = Value(in.mass);
  auto center = LengthVector(in.center);
  if (mass && !(*mass > 0)) Error(ptr + "/mass", "mass must be positive", "give the body's mass in units/mass");
  // Beyond 1e15 kg the inverse dynamics (m·a, m·L² with lengths up to 1e12 m) leaves
  // the doubles' range: a mass of 1e308 gave NaN efforts and exit 0.
  constexpr double kMaxMass = 1e15;  // kg
  if (mass && *mass * model_.units.mass_to_si > kMaxMass) {
    Error(ptr + "/mass", "mass " + FormatNumber(*mass) + " " + model_.units.mass_name + " is beyond 1e15 kg",
          "check the number and the mass unit");
    return std::nullopt;
  }
  if (!mass || !(*mass > 0) || !center) return std::nullopt;
  const Mat3 A = CalcA(euler);
  out.mass = *mass * model_.units.mass_to_si;
  out.center = A.transpose() * (*center - r);
  const double scale = model_.units.mass_to_si * length_ * length_;
  if (in.has_moments == (in.has_principal || in.has_axes)) {
    Error(ptr, "give either 'moments' or 'principal' with 'axes'",
          "moments: [[Ixx,Ixy,Ixz],[Ixy,Iyy,Iyz],[Ixz,Iyz,Izz]] about the centre, in global design axes");
    return std::nullopt;
  }
  std::optional<Mat3> J = in.has_moments ? CompileMatrix(in.moments, in.moments_error, ptr + "/moments")
                                         : CompilePrincipal(in);
  if (!J) return std::nullopt;
  *J *= scale;
  if (!CheckInertiaTensor(*J, ptr)) return std::nullopt;
  out.moments = A.transpose() * *J * A;
  return out;
}

std::optional<Mat3> Compiler::CompileMatrix(const std::optional<std::array<Vector3Spec, 3>>& rows,
                                            const std::string& error, const std::string& ptr) {
  if (!rows) {
    Error(ptr, error);
    return std::nullopt;
  }
  Mat3 out;
  for (int i = 0; i < 3; ++i) {
    auto row = VectorValue((*rows)[i], false);
    if (!row) return std::nullopt;
    out.row(i) = row->transpose();
  }
  return out;
}

std::optional<Mat3> Compiler::CompilePrincipal(const InertiaSpec& in) {
  const std::string& ptr = in.pointer;
  auto p = Vector(in.principal, false);
  if (!in.has_axes) Error(ptr + "/axes", "'principal' needs 'axes'", "give the 3 principal axes (rows)");
  if (!p || !in.has_axes) return std::nullopt;
  auto axes = CompileMatrix(in.axes, in.axes_error, ptr + "/axes");
  if (!axes) return std::nullopt;
  Mat3 U;
  for (int k = 0; k < 3; ++k) U.col(k) = axes->row(k).transpose().normalized();
  if ((U.transpose() * U - Mat3::Identity()).norm() > 1e-6) {
    Error(ptr + "/axes", "principal axes are not perpendicular", "give three perpendicular axes");
    return std::nullopt;
  }
  return U * p->asDiagonal() * U.transpose();
}

bool Compiler::CheckInertiaTensor(const Mat3& J, const std::string& ptr) {
  const double size = J.cwiseAbs().maxCoeff();
  if ((J - J.transpose()).cwiseAbs().maxCoeff() > 1e-9 * size) {
    Error(ptr + "/moments", "the inertia tensor is not symmetric", "Ixy must equal Iyx, and so on");
    return false;
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(J);
  const Vec3 I = eig.eigenvalues();
  if (I.minCoeff() < -1e-12 * size || I[0] + I[1] < I[2] * (1 - 1e-9)) {
    Error(ptr, "the inertia tensor is not physical (principal moments " + FormatNumber(I[0]) + ", " +
                   FormatNumber(I[1]) + ", " + FormatNumber(I[2]) + " must be ≥ 0 and obey I1 + I2 ≥ I3)",
          "check the moments and their units (mass × length², about the centre of mass)");
    return false;
  }
  return true;
}

}  // namespace mechkin
