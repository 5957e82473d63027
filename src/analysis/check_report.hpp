// The typed result of `mechkin check` for one file: validation diagnostics,
// counts, the Grübler–Kutzbach count, the rank-based mobility report and the
// file's `expect` assertions. Every front end (CLI text and JSON, Python) reads
// this object; the renderers live in io/check_report_writer.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/branches.hpp"
#include "analysis/kinematic_analysis.hpp"
#include "mobility/grubler.hpp"
#include "mobility/mobility.hpp"
#include "analysis/load.hpp"
#include "analysis/reduction_result.hpp"

namespace mechkin {

/// An expected or actual value of an `expect` key: a count, a word, or absent
/// (not computed, e.g. when the design pose does not assemble).
struct ExpectValue {
  enum class Kind { Absent, Count, Word, Number } kind = Kind::Absent;
  int count = 0;
  std::string word;
  double number = 0;  // Number: a length in the file's unit (min_clearance)
  static ExpectValue Of(int n) { return {Kind::Count, n, "", 0}; }
  static ExpectValue Of(const std::string& w) { return {Kind::Word, 0, w, 0}; }
  static ExpectValue Of(double x) { return {Kind::Number, 0, "", x}; }
  bool operator==(const ExpectValue& o) const {
    return kind == o.kind && count == o.count && word == o.word && number == o.number;
  }
};

struct ExpectationResult {
  std::string key;  // grubler, mobility, redundant, idle, driven, min_clearance
  ExpectValue expected, actual;
  bool held = false;
  std::string where;  // min_clearance: the tightest pair and where ("" for the others)
};

/// `check --clearance` (analysis/clearance_sweep.hpp), in the file's length unit.
struct ClearanceSection {
  struct Pair { std::string body1, body2, output; double clearance, t; std::string where; };
  std::vector<Pair> pairs;
  int tightest = -1;  // index into pairs (−1: none)
  int rows = 0;
  bool complete = false;
  std::string note, length_unit;
};

/// What the file's numbers make of each body (issue "Parametric designs", item 2):
/// distances between its joint points and angles between its joint axes, in the
/// file's units, so a slip (a point typed in m in a mm file) shows before a run.
struct BodyGeometry {
  struct Length { std::string joint1, joint2; double value; };
  struct AxisAngle { std::string joint1, joint2; double value; };  // between the joints' axes
  std::string body;
  std::vector<Length> lengths;
  std::vector<AxisAngle> angles;
};

/// How a file placed by its markers was assembled (analysis/assemble_model.hpp), in
/// the file's units: per loop the closure error before and after, and per body how
/// far it moved from its guess (the sketch or the tree placement).
struct AssemblySection {
  struct Loop { std::string joint, name; std::vector<std::string> path; double error_before, error_after; };
  struct Move { std::string body; bool sketched; double distance, angle; };
  std::vector<Loop> loops;
  std::vector<Move> moves;
  int iterations = 0;
};

struct CheckReport {
  std::string file;
  bool valid = false;
  std::vector<Diagnostic> errors, warnings;
  std::string name;
  int bodies = 0, drivers = 0;
  std::vector<std::pair<std::string, int>> joints;  // type name → count, in first-seen order
  int grubler = 0;
  int couplers = 0, joint_equations = 0;  // the count's terms: 6·bodies − joint_equations − couplers
  int dof_after_drivers_count = 0;  // Grübler count − drivers
  std::optional<PlanarStructure> planar;  // a planar mechanism: its plane and planar count
  std::optional<MobilityReport> mobility;
  std::vector<ExpectationResult> expectations;
  std::vector<BodyGeometry> geometry;       // per moving body with two or more joints
  std::vector<Parameter> parameters;        // resolved values
  std::string length_unit, angle_unit;      // of geometry and parameters
  std::optional<BranchCount> branches;      // with `check --branches`
  std::optional<AssemblySection> assembly;  // files placed by markers only
  std::optional<ClearanceSection> clearance;  // with `check --clearance` or expect min_clearance
  /// Valid and every expectation held.
  bool ok() const;
};

/// Sweeps the clearances into r->clearance and checks expect min_clearance
/// (analysis/clearance_sweep.cpp); `stop` is polled every step (true: the sweep ends).
void AddClearanceCheck(const Model& m, CheckReport* r, const InterruptPoll& stop = {});

class MotionLayout;
/// `expect: {"min": {name: v}, "max": {...}}` (docs/format.md "Assertions on the
/// motion"): the bounds as min/max reductions (each named by its key "min/name").
std::vector<Reduction> BoundReductions(const Model& m);
/// Each bound against its reduction over a run in `layout` (`results` from
/// BoundReductions, in order); `stopped`: why the run ended early ("" complete).
std::vector<ExpectationResult> BoundExpectations(const Model& m, const MotionLayout& layout,
                                                 const std::vector<ReductionResult>& results,
                                                 const std::string& stopped);
/// `check`: runs the motion (outputs only, file units) and appends the bounds' results.
void AddMotionBoundCheck(const Model& m, CheckReport* r, const InterruptPoll& stop = {});
/// Checks one loaded file (never throws for bad input).
CheckReport CheckLoaded(const std::string& file, const LoadResult& loaded);
/// Thrown by the stoppable check (CheckLoaded with a poll, analysis/check_file.hpp)
/// when its poll turns true: the stage it was in ("the mobility analysis", ...).
struct CheckStopped {
  const char* stage;
};
/// As above, asking `stop` between the check's stages (and every step of a clearance
/// sweep): true abandons the check with CheckStopped.
CheckReport CheckLoaded(const std::string& file, const LoadResult& loaded, const InterruptPoll& stop);
/// Throws CheckStopped{stage} when `stop` is set and returns true.
void StopPoint(const InterruptPoll& stop, const char* stage);
/// Reads and checks one file.
CheckReport CheckFile(const std::string& path);

}  // namespace mechkin
