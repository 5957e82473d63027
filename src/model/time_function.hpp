// Driver functions of time (format-v1 "function"): an expression in t or a
// table. Both return exact derivatives to the 4th order as a Jet.
#pragma once

#include <array>
#include <map>
#include <stdexcept>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "math/taylor.hpp"

namespace mechkin {

/// Bad expression text; `column` is 1-based in the expression string.
struct ExpressionError : std::runtime_error {
  ExpressionError(const std::string& what, int column, std::string unknown_name = "")
      : std::runtime_error(what), column(column), unknown_name(std::move(unknown_name)) {}
  int column;
  std::string unknown_name;  // set when the error is an unknown name (for did-you-mean)
};

/// Named constants an expression may use besides t and pi (the file's parameters).
using ExpressionSymbols = std::map<std::string, double>;
/// Parameter name → slot index, for expressions parsed once and valued per variant.
using ExpressionSlots = std::unordered_map<std::string, int>;

/// A parsed expression in `t`. Grammar (format-v1): + - * / ^ (right-assoc.,
/// binds tighter than unary minus), parentheses, numbers, `t`, `pi`, and
/// sin cos tan asin acos atan atan2 exp log sqrt.
class Expression {
 public:
  static constexpr int kMaxNesting = 64;       // parentheses / calls / signs / powers
  static constexpr size_t kMaxLength = 65536;  // characters
  /// Throws ExpressionError naming the column of the bad token. `symbols`: named
  /// constants (parameters) replaced by their values; `allow_time` false for
  /// expressions that must be constants (numbers of the geometry).
  static Expression Parse(const std::string& text, const ExpressionSymbols* symbols = nullptr,
                          bool allow_time = true);
  /// Parses once for many parameter values: the names in `slots` (parameter name →
  /// slot) stay symbolic, valued by EvalWithSlots. Throws as Parse; Eval of such an
  /// expression gives NaN for the slots.
  static Expression ParseWithSlots(const std::string& text, const ExpressionSlots& slots, bool allow_time);
  /// Value and derivatives at t with slot k valued slot_values[k] (the same numbers
  /// as Parse with those values substituted, then Eval).
  Jet EvalWithSlots(double t, const std::vector<double>& slot_values) const;
  /// An output's "expression" (docs/format.md "Expression outputs"): `symbols` (the
  /// parameters) become constants, `slots` are the columns it reads, whose names may
  /// carry one ".component" ("tip.x"). Throws as Parse.
  static Expression ParseOverColumns(const std::string& text, const ExpressionSymbols& symbols,
                                     const ExpressionSlots& slots);
  /// Value and derivatives at t with slot k the jet slot_jets[k] (a column's value and
  /// time derivatives): the chain rule to the 4th order. Throws JetDomainError.
  Jet EvalWithSlotJets(double t, const std::vector<Jet>& slot_jets) const;
  /// Names as ParseOverColumns reads them ("tip.x" one name), reserved ones left out.
  static std::vector<std::string> DottedNames(const std::string& text);
  /// The slots the expression uses, each once, in order of first use.
  std::vector<int> SlotsUsed() const;
  /// Identifiers reserved by the grammar (t, pi and the function names).
  static bool IsReservedName(const std::string& name);
  /// The names an expression uses besides the reserved ones (its parameters), found
  /// by scanning alone: no parse, no exception, whatever the text.
  static std::vector<std::string> Names(const std::string& text);
  /// Value and derivatives at t. Throws JetDomainError outside the domain.
  Jet Eval(double t) const;
  /// The value alone at t in extended precision (long double), for the accuracy phase
  /// of the position solve. The constants are the parsed doubles; call after Eval
  /// succeeded at t (no domain checks of its own: a NaN there means "use Eval's").
  long double ValueExtended(double t) const;
  const std::string& text() const { return text_; }

 private:
  enum class Op { Const, Time, Slot, Neg, Add, Sub, Mul, Div, Pow, Sin, Cos, Tan, Asin, Acos, Atan,
                  Atan2, Exp, Log, Sqrt };
  struct Node { Op op; double value = 0; int a = -1, b = -1; };
  /// One node on jets (Eval) or on long double values (ValueExtended).
  template <typename V>
  static V EvalNode(const Node& node, const V& t, const std::vector<V>& values);
  friend class ExpressionParser;
  std::string text_;
  std::vector<Node> nodes_;
  int root_ = -1;
};

/// How a table is interpolated: quintic (default: C4, natural ends v''' = v'''' = 0,
/// the minimiser of the integral of (v''')^2), cubic (C2, natural ends v'' = 0) or
/// linear (C0: the velocity jumps at the knots). Two rows are always joined linearly.
enum class Interpolation { Quintic, Cubic, Linear };

/// Interpolating spline through (t_k, v_k), one polynomial of degree <= 5 per interval.
class TableSpline {
 public:
  /// Requires >= 2 points with strictly increasing, finite t. Throws std::invalid_argument.
  TableSpline(std::vector<double> t, std::vector<double> v, Interpolation how = Interpolation::Quintic);
  /// Throws std::out_of_range outside [t_front, t_back].
  Jet Eval(double t) const;
  double t_min() const { return t_.front(); }
  double t_max() const { return t_.back(); }
  /// The largest excursion of the interpolant beyond the values at the two ends
  /// of an interval, and that interval's index (a staircase table rings).
  double MaxOvershoot(int* interval) const;
  double knot(int k) const { return t_[k]; }
  double ValueRange() const;

 private:
  void BuildQuintic();
  void BuildCubic();
  void BuildLinear();
  std::vector<double> t_, v_;
  std::vector<std::array<double, 6>> poly_;  // per interval, coefficients in (t - t_k)
};

/// A driver function: one of the two forms, scaled to SI by `scale`.
class TimeFunction {
 public:
  TimeFunction() = default;
  TimeFunction(std::shared_ptr<const Expression> e, double scale) : expr_(std::move(e)), scale_(scale) {}
  TimeFunction(std::shared_ptr<const TableSpline> s, double scale) : table_(std::move(s)), scale_(scale) {}
  /// Value and derivatives (SI) at t.
  Jet Eval(double t) const;
  /// The value (SI) at t in extended precision: expressions evaluated in long double,
  /// tables (double data) as Eval's value. Falls back to Eval's value if not finite.
  long double ValueExtended(double t) const;
  bool is_table() const { return table_ != nullptr; }
  std::string Describe() const;

 private:
  std::shared_ptr<const Expression> expr_;
  std::shared_ptr<const TableSpline> table_;
  double scale_ = 1.0;
};

}  // namespace mechkin
