// Every enum ↔ string pair the front ends read or write (CLI options, table and
// report formats, the Python binding, diagnostics), in one place: ToString(e)
// gives the name as a user types it, Parse(text, &e) the reverse, NamesOf<E>()
// every name in declaration order (for CLI11's IsMember and error messages).
#pragma once

#include <string>
#include <vector>

#include "analysis/check_file.hpp"
#include "analysis/kinematic_analysis.hpp"
#include "analysis/motion.hpp"
#include "analysis/run_request.hpp"
#include "mobility/mobility.hpp"
#include "model/model.hpp"

namespace mechkin {

/// Format of a motion table (`run --format`, Motion.to_csv/to_json).
enum class TableFormat { Csv, Json };
/// Format of a report (`check`, `range`, `tolerance --format`).
enum class ReportFormat { Text, Json };
/// Format of `check --format`: the reports, plus the forms for many files and for CI
/// (JSON lines, SARIF 2.1.0, compiler-style `file:line:col: error: ...` lines).
enum class CheckFormat { Text, Json, Jsonl, Sarif, Gcc };

template <typename E>
struct EnumName {
  E value;
  const char* name;
};

/// The names of an enum; specialised below for every enum with a user-visible name.
template <typename E>
struct EnumNames;

template <>
struct EnumNames<Formulation> {
  static constexpr EnumName<Formulation> kAll[] = {{Formulation::Omega, "omega"}, {Formulation::P, "p"}};
};
template <>
struct EnumNames<PositionSolver> {
  static constexpr EnumName<PositionSolver> kAll[] = {{PositionSolver::Newton, "newton"},
                                                      {PositionSolver::Ceres, "ceres"}};
};
template <>
struct EnumNames<TableFormat> {
  static constexpr EnumName<TableFormat> kAll[] = {{TableFormat::Csv, "csv"}, {TableFormat::Json, "json"}};
};
template <>
struct EnumNames<ReportFormat> {
  static constexpr EnumName<ReportFormat> kAll[] = {{ReportFormat::Text, "text"}, {ReportFormat::Json, "json"}};
};
template <>
struct EnumNames<CheckFormat> {
  static constexpr EnumName<CheckFormat> kAll[] = {{CheckFormat::Text, "text"},
                                                   {CheckFormat::Json, "json"},
                                                   {CheckFormat::Jsonl, "jsonl"},
                                                   {CheckFormat::Sarif, "sarif"},
                                                   {CheckFormat::Gcc, "gcc"}};
};
// A checked file's verdict (`check --format jsonl`, the summary).
template <>
struct EnumNames<CheckVerdict> {
  static constexpr EnumName<CheckVerdict> kAll[] = {{CheckVerdict::Ok, "ok"},
                                                    {CheckVerdict::Failed, "failed"},
                                                    {CheckVerdict::Invalid, "invalid"},
                                                    {CheckVerdict::Timeout, "timeout"},
                                                    {CheckVerdict::Error, "error"}};
};
// Why a run ended (Python's RunStop.kind, pickled motions).
template <>
struct EnumNames<StopKind> {
  static constexpr EnumName<StopKind> kAll[] = {{StopKind::None, "none"},
                                                {StopKind::Refused, "refused"},
                                                {StopKind::AssemblyFailed, "assembly_failed"},
                                                {StopKind::SingularPosition, "singular_position"},
                                                {StopKind::SolveFailed, "solve_failed"},
                                                {StopKind::Interrupted, "interrupted"},
                                                {StopKind::JointLimit, "joint_limit"},
                                                {StopKind::Contact, "contact"}};
};
// At a joint's limits (`run --on-limit`, Python's Model.run(on_limit=...)).
template <>
struct EnumNames<LimitAction> {
  static constexpr EnumName<LimitAction> kAll[] = {{LimitAction::Stop, "stop"}, {LimitAction::Report, "report"}};
};
// At a first contact of a clearance output's bodies (`run --on-contact`).
template <>
struct EnumNames<ContactAction> {
  static constexpr EnumName<ContactAction> kAll[] = {{ContactAction::Stop, "stop"}, {ContactAction::Report, "report"}};
};
// Which rows have measured error bounds (`run --error-bounds`, Python's error_bounds).
template <>
struct EnumNames<ErrorBoundsChoice> {
  static constexpr EnumName<ErrorBoundsChoice> kAll[] = {{ErrorBoundsChoice::Auto, "auto"},
                                                         {ErrorBoundsChoice::Measured, "measured"}};
};
// `check`'s driving status (the `expect` key "driven").
template <>
struct EnumNames<DrivingStatus> {
  static constexpr EnumName<DrivingStatus> kAll[] = {
      {DrivingStatus::Full, "full"}, {DrivingStatus::Under, "under"}, {DrivingStatus::Over, "over"}};
};
// A motion column's quantity (Python's column descriptors).
template <>
struct EnumNames<Quantity> {
  static constexpr EnumName<Quantity> kAll[] = {
      {Quantity::Time, "time"},
      {Quantity::BodyPosition, "body_position"},
      {Quantity::EulerParameter, "euler_parameter"},
      {Quantity::AngularVelocity, "angular_velocity"},
      {Quantity::PointPosition, "point"},
      {Quantity::Distance, "distance"},
      {Quantity::JointAngle, "joint_angle"},
      {Quantity::JointSlide, "joint_slide"},
      {Quantity::Angle, "angle"},
      {Quantity::VelocityRatio, "velocity_ratio"},
      {Quantity::OrientationAngle, "orientation_angle"},
      {Quantity::OrientationParameter, "orientation_parameter"},
      {Quantity::RotationVector, "rotation_vector"},
      {Quantity::GimbalLock, "gimbal_lock"},
      {Quantity::Clearance, "clearance"},
      {Quantity::ClearancePoint, "clearance_point"},
      {Quantity::Expression, "expression"},
      {Quantity::DriverEffort, "driver_effort"},
      {Quantity::DriverPower, "driver_power"},
      {Quantity::JointForce, "joint_force"},
      {Quantity::JointMoment, "joint_moment"},
      {Quantity::JointForceLocal, "joint_force_local"},
      {Quantity::JointMomentLocal, "joint_moment_local"},
      {Quantity::CouplerEffort, "coupler_effort"},
      {Quantity::CouplerPower, "coupler_power"},
      {Quantity::KineticEnergy, "kinetic_energy"},
      {Quantity::PotentialEnergy, "potential_energy"},
      {Quantity::EnergyBalance, "energy_balance"},
      {Quantity::NewtonIterations, "newton_iterations"},
      {Quantity::Residual, "residual"},
      {Quantity::Condition, "condition"},
      {Quantity::ErrorBound, "error_bound"}};
};

/// The name of `value` ("" for a value without one).
template <typename E>
const char* ToString(E value) {
  for (const auto& e : EnumNames<E>::kAll)
    if (e.value == value) return e.name;
  return "";
}

/// The value named `text` (exact, lower case); false and *value untouched when none is.
template <typename E>
bool Parse(const std::string& text, E* value) {
  for (const auto& e : EnumNames<E>::kAll)
    if (text == e.name) {
      *value = e.value;
      return true;
    }
  return false;
}

/// Every name, in declaration order.
template <typename E>
std::vector<std::string> NamesOf() {
  std::vector<std::string> names;
  for (const auto& e : EnumNames<E>::kAll) names.push_back(e.name);
  return names;
}

/// "omega, p": the names for a message.
template <typename E>
std::string NameList() {
  std::string s;
  for (const auto& e : EnumNames<E>::kAll) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

}  // namespace mechkin
