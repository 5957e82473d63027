#include "output/motion_table.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace mechkin {
namespace {

const char* kSuffix[] = {"", "_t", "_tt", "_ttt", "_tttt"};
const char* kPer[] = {"", "/s", "/s^2", "/s^3", "/s^4"};

std::string Col(const std::string& name, int k, const std::string& unit) {
  std::string u = unit.empty() ? (k ? std::string("1") + kPer[k] : "") : unit + kPer[k];
  return name + kSuffix[k] + (u.empty() ? "" : " [" + u + "]");
}

// Jet of a vector component from its derivatives (for products and norms of
// derivative series: slides and distances).
std::array<Jet, 3> VecJet(const Vec3* d, int order) {
  std::array<Jet, 3> j;
  static constexpr double kInvFact[] = {1, 1, 0.5, 1.0 / 6, 1.0 / 24};
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k <= order; ++k) j[a].c[k] = d[k][a] * kInvFact[k];
  return j;
}

}  // namespace

MotionTable::MotionTable(const Model& model, const TableOptions& options)
    : model_(model), options_(options), angle_ref_(model.outputs.size(), 0.0) {
  if (!options.si) {
    len_ = 1 / model.units.length_to_si;
    ang_ = 1 / model.units.angle_to_si;
  }
  const std::string L = options.si ? "m" : model.units.length_name, A = options.si ? "rad" : model.units.angle_name;
  const int order = options.order;
  header_.push_back("t [s]");
  auto add_series = [&](const std::string& name, const std::string& unit, int first) {
    for (int k = first; k <= order; ++k) header_.push_back(Col(name, k, unit));
  };
  for (int b = 0; b < model.num_bodies(); ++b) {
    const std::string& nm = model.bodies[b].name;
    if (!options.all_bodies && std::find(options.bodies.begin(), options.bodies.end(), nm) == options.bodies.end()) continue;
    items_.push_back({0, b});
    for (const char* c : {".x", ".y", ".z"}) add_series(nm + c, L, 0);
    for (const char* c : {".e0", ".e1", ".e2", ".e3"}) header_.push_back(nm + c);
    // Angular velocity and its derivatives: column ".wx" is order 1.
    for (const char* c : {".wx", ".wy", ".wz"})
      for (int k = 1; k <= order; ++k) header_.push_back(nm + c + kSuffix[k - 1] + " [" + A + kPer[k] + "]");
  }
  for (const auto& sel : options.bodies)
    if (!options.all_bodies && std::none_of(model.bodies.begin(), model.bodies.end(), [&](const Body& b) { return b.name == sel; }))
      throw std::invalid_argument("--bodies: no body named '" + sel + "'");
  for (size_t o = 0; o < model.outputs.size(); ++o) {
    const Output& out = model.outputs[o];
    if (!options.all_outputs && std::find(options.outputs.begin(), options.outputs.end(), out.name) == options.outputs.end()) continue;
    items_.push_back({1, static_cast<int>(o)});
    if (out.kind == OutputKind::Point) {
      for (const char* c : {".x", ".y", ".z"}) add_series(out.name + c, L, 0);
    } else if (out.kind == OutputKind::Distance) {
      add_series(out.name, L, 0);
    } else {
      const JointType jt = model.joints[out.joint].type;
      if (jt == JointType::Revolute) add_series(out.name, A, 0);
      else if (jt == JointType::Prismatic) add_series(out.name, L, 0);
      else { add_series(out.name + ".angle", A, 0); add_series(out.name + ".slide", L, 0); }
    }
  }
  for (const auto& sel : options.outputs)
    if (!options.all_outputs && std::none_of(model.outputs.begin(), model.outputs.end(), [&](const Output& o) { return o.name == sel; }))
      throw std::invalid_argument("--outputs: no output named '" + sel + "'");
  header_.push_back("newton_iterations");
  header_.push_back("residual");
  header_.push_back("condition");
  for (int k = 0; k <= order; ++k) header_.push_back(std::string("error_bound") + kSuffix[k]);
}

void MotionTable::AddRow(const SystemState& s, double t, int iterations, double residual, double condition,
                         const double* error_bound) {
  const int order = options_.order;
  std::vector<double> row;
  row.reserve(header_.size());
  row.push_back(t);
  for (const Item& it : items_) {
    if (it.kind == 0) {
      const BodyKinematics& b = s.bodies[it.index];
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k <= order; ++k) row.push_back(b.r[k][a] * len_);
      for (int a = 0; a < 4; ++a) row.push_back(b.p[a]);
      // Global angular velocity and derivatives: ω = Aω', ω̇ = Aω̇', ω̈ = A(ω̈' + ω'×ω̇'),
      // ω⃛ = A(ω⃛' + 2ω'×ω̈' + ω'×(ω'×ω̇')).
      Vec3 wg[4];
      wg[0] = b.A * b.w[0];
      wg[1] = b.A * b.w[1];
      wg[2] = b.A * (b.w[2] + b.w[0].cross(b.w[1]));
      wg[3] = b.A * (b.w[3] + 2 * b.w[0].cross(b.w[2]) + b.w[0].cross(b.w[0].cross(b.w[1])));
      for (int a = 0; a < 3; ++a)
        for (int k = 1; k <= order; ++k) row.push_back(wg[k - 1][a] * ang_);
      continue;
    }
    const Output& out = model_.outputs[it.index];
    const BodyKinematics& b1 = s.Kin(out.body1);
    const BodyKinematics& b2 = s.Kin(out.body2);
    if (out.kind == OutputKind::Point) {
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k <= order; ++k) row.push_back(b1.PointDerivative(out.point1, k)[a] * len_);
    } else if (out.kind == OutputKind::Distance) {
      Vec3 d[5];
      for (int k = 0; k <= order; ++k) d[k] = b2.PointDerivative(out.point2, k) - b1.PointDerivative(out.point1, k);
      const auto j = VecJet(d, order);
      const Jet dist = Sqrt(j[0] * j[0] + j[1] * j[1] + j[2] * j[2]);
      for (int k = 0; k <= order; ++k) row.push_back(dist.Derivative(k) * len_);
    } else {
      const Joint& jt = model_.joints[out.joint];
      const bool angle = jt.type != JointType::Prismatic, slide = jt.type != JointType::Revolute;
      if (angle) {
        // θ = atan2(g_iᵀf_j, f_iᵀf_j), continuous; θ^(k) = h'_jᵀω_j'^(k−1) − h'_iᵀω_i'^(k−1) on the joint.
        const Vec3 fj = b2.A * jt.frame2.f;
        const double th = UnwrapAngle((b1.A * jt.frame1.g).dot(fj), (b1.A * jt.frame1.f).dot(fj), angle_ref_[it.index]);
        angle_ref_[it.index] = th;
        row.push_back(th * ang_);
        for (int k = 1; k <= order; ++k)
          row.push_back((jt.frame2.h.dot(b2.w[k - 1]) - jt.frame1.h.dot(b1.w[k - 1])) * ang_);
      }
      if (slide) {
        // s = h_iᵀ(P_j − P_i), differentiated by the Leibniz rule on jets.
        Vec3 d[5], hv[5];
        for (int k = 0; k <= order; ++k) {
          d[k] = b2.PointDerivative(jt.frame2.origin, k) - b1.PointDerivative(jt.frame1.origin, k);
          hv[k] = b1.VectorDerivative(jt.frame1.h, k);
        }
        const auto jd = VecJet(d, order), jh = VecJet(hv, order);
        const Jet sl = jh[0] * jd[0] + jh[1] * jd[1] + jh[2] * jd[2];
        for (int k = 0; k <= order; ++k) row.push_back(sl.Derivative(k) * len_);
      }
    }
  }
  row.push_back(iterations);
  row.push_back(residual);
  row.push_back(condition);
  for (int k = 0; k <= order; ++k) row.push_back(error_bound ? error_bound[k] : 0.0);
  rows_.push_back(std::move(row));
}

void MotionTable::WriteCsv(std::ostream& out, bool partial, const std::string& note) const {
  if (partial) out << "# PARTIAL TABLE: " << note << "\n";
  for (size_t c = 0; c < header_.size(); ++c) out << (c ? "," : "") << header_[c];
  out << "\n";
  char buf[40];
  for (const auto& row : rows_) {
    for (size_t c = 0; c < row.size(); ++c) {
      std::snprintf(buf, sizeof buf, "%.17g", row[c]);
      out << (c ? "," : "") << buf;
    }
    out << "\n";
  }
}

void MotionTable::WriteJson(std::ostream& out, bool partial, const std::string& note) const {
  nlohmann::json j;
  j["mechkin_table"] = 1;
  j["partial"] = partial;
  if (partial) j["note"] = note;
  j["columns"] = nlohmann::json::array();
  for (const auto& h : header_) {
    const auto lb = h.find(" [");
    j["columns"].push_back({{"name", h.substr(0, lb)}, {"unit", lb == std::string::npos ? "" : h.substr(lb + 2, h.size() - lb - 3)}});
  }
  j["rows"] = rows_;
  out << j.dump() << "\n";
}

bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) { *error = "cannot write '" + tmp + "'"; return false; }
    f << content;
    f.flush();
    if (!f) { *error = "write to '" + tmp + "' failed"; std::remove(tmp.c_str()); return false; }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    *error = "cannot rename '" + tmp + "' to '" + path + "'";
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace mechkin
