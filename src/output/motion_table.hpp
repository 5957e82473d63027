// The motion table: one row per time step, columns named exactly as in
// format-v1 "Motion table columns" (`t [s]`, `crank.x [mm]`, `crank.e0`,
// `crank.wx [deg/s]`, `piston.x_tt [mm/s^2]`, `crank_angle_ttt [deg/s^3]`, ...),
// followed by the step diagnostics `newton_iterations`, `residual`, `condition`
// and `error_bound`, `error_bound_t`, … (relative error bounds per order).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "constraints/system.hpp"

namespace mechkin {

struct TableOptions {
  int order = 3;
  bool si = false;
  bool all_bodies = true, all_outputs = true;
  std::vector<std::string> bodies, outputs;  // selections when not all
};

class MotionTable {
 public:
  /// Throws std::invalid_argument for a selected body/output that does not exist.
  MotionTable(const Model& model, const TableOptions& options);

  const std::vector<std::string>& header() const { return header_; }
  const std::vector<std::vector<double>>& rows() const { return rows_; }
  /// Appends the row of state `s` (values converted to the table's units).
  void AddRow(const SystemState& s, double t, int iterations, double residual, double condition = 0,
              const double* error_bound = nullptr);

  void WriteCsv(std::ostream& out, bool partial, const std::string& note) const;
  void WriteJson(std::ostream& out, bool partial, const std::string& note) const;

 private:
  struct Item { int kind; int index; };  // kind 0 body, 1 output
  const Model& model_;
  TableOptions options_;
  std::vector<Item> items_;
  std::vector<std::string> header_;
  std::vector<std::vector<double>> rows_;
  std::vector<double> angle_ref_;  // per output, for continuous joint angles
  double len_ = 1, ang_ = 1;       // SI → table unit factors
};

/// Writes `content` to `path` through a temporary file in the same folder and a
/// rename, so that `path` is never half written. Returns false with a message.
bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error);

}  // namespace mechkin
