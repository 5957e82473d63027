// The expressions of one spec, parsed once and shared by every model compiled from
// it: a sweep row, a tolerance sample, a sensitivity side or `with_parameters`
// re-evaluates them with its own parameter values instead of parsing the text again.
//
// Entries are keyed by the address of the text inside the (immutable, shared) spec.
// The first compile of a spec records them; the cache is then frozen (const) and
// read concurrently by variant compiles. A text it does not hold is parsed as before.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/time_function.hpp"

namespace mechkin {

struct MechanismSpec;

class ExpressionCache {
 public:
  /// A constant of the geometry: parsed with the parameters as slots.
  struct Constant {
    Expression expression;
    std::vector<int> slots;  // the slots it uses
  };

  /// Slots for the spec's parameters, in declaration order.
  explicit ExpressionCache(const MechanismSpec& spec);
  /// The spec whose texts the entries point into (a cache serves that spec only).
  const MechanismSpec* spec() const { return spec_; }

  const ExpressionSlots& slots() const { return slots_; }
  int num_slots() const { return static_cast<int>(slots_.size()); }
  const Constant* FindConstant(const std::string* text) const;
  /// A function of time that uses no parameter: the same parsed expression serves
  /// every variant.
  std::shared_ptr<const Expression> FindTimeFunction(const std::string* text) const;
  /// The parameter names a text uses (Expression::Names), when recorded.
  const std::vector<std::string>* FindNames(const std::string* text) const;

  // Recording (the first compile only, before the cache is shared).
  const Constant* RecordConstant(const std::string* text, Expression expression);
  void RecordTimeFunction(const std::string* text, std::shared_ptr<const Expression> expression);
  const std::vector<std::string>& RecordNames(const std::string* text);

 private:
  const MechanismSpec* spec_;
  ExpressionSlots slots_;
  std::unordered_map<const std::string*, Constant> constants_;
  std::unordered_map<const std::string*, std::shared_ptr<const Expression>> time_functions_;
  std::unordered_map<const std::string*, std::vector<std::string>> names_;
};

}  // namespace mechkin
