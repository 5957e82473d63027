// Parameters: resolved in dependency order (Kahn's algorithm on the graph of the
// names each expression uses), each expression scanned and parsed once, so that
// a chain of n parameters costs O(n log n), not O(n²) passes.
#include <algorithm>
#include <deque>
#include <unordered_map>

#include "model/compiler.hpp"

namespace mechkin {

void Compiler::CompileParameters() {
  out_.SetPlace(Section::Parameters);
  std::vector<size_t> pending;  // spec indices of the declarations with a value
  for (size_t i = 0; i < spec_.parameters.size(); ++i) {
    const ParameterSpec& ps = spec_.parameters[i];
    if (Expression::IsReservedName(ps.name)) {
      Error("/parameters/" + EscapeToken(ps.name), "invalid parameter name '" + Shorten(ps.name) + "'",
            "use 1-64 letters, digits or '_', starting with a letter or '_', other than t, pi and the "
            "function names");
      continue;
    }
    Parameter param;
    param.name = ps.name;
    param.tolerance = ps.tolerance;
    param.min = ps.min;
    param.max = ps.max;
    if (ps.value && ps.value->kind == Scalar::Kind::Expression) param.expression = ps.value->text;
    param.overridden = overrides_.count(ps.name) > 0 && ps.value;
    model_.parameters.push_back(param);
    if (ps.value) pending.push_back(i);
  }
  ResolveParameters(pending);
  for (Parameter& p : model_.parameters)
    if (const auto it = symbols_.find(p.name); it != symbols_.end()) p.value = it->second;
  for (const auto& kv : overrides_)
    if (!model_.FindParameter(kv.first)) {
      std::vector<std::string> names;
      for (const auto& p : model_.parameters) names.push_back(p.name);
      const std::string guess = DidYouMean(kv.first, names);
      Error("/parameters", "no parameter '" + Shorten(kv.first) + "' to set",
            guess.empty() ? (names.empty() ? "the file declares no parameters" : "parameters: " + Join(names))
                          : "did you mean '" + guess + "'?");
    }
}

// Kahn: a parameter is evaluated once every parameter its expression names is;
// what never becomes ready lies on (or behind) a cycle.
void Compiler::ResolveParameters(const std::vector<size_t>& pending) {
  const size_t n = pending.size();
  std::unordered_map<std::string, size_t> node_of;
  for (size_t k = 0; k < n; ++k) node_of.emplace(spec_.parameters[pending[k]].name, k);
  std::vector<std::vector<size_t>> deps(n), dependents(n);
  std::vector<size_t> waiting_on(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const ParameterSpec& ps = spec_.parameters[pending[k]];
    if (ps.value->kind != Scalar::Kind::Expression || overrides_.count(ps.name)) continue;
    for (const std::string& used : NamesUsed(ps.value->text)) {
      const auto it = node_of.find(used);
      if (it == node_of.end() || it->second == k) continue;
      if (std::find(deps[k].begin(), deps[k].end(), it->second) != deps[k].end()) continue;
      deps[k].push_back(it->second);
      dependents[it->second].push_back(k);
    }
    waiting_on[k] = deps[k].size();
  }
  std::deque<size_t> ready;
  for (size_t k = 0; k < n; ++k)
    if (waiting_on[k] == 0) ready.push_back(k);
  while (!ready.empty()) {
    const size_t k = ready.front();
    ready.pop_front();
    if (!ResolveParameter(spec_.parameters[pending[k]])) failed_parameters_.insert(spec_.parameters[pending[k]].name);
    for (size_t d : dependents[k])
      if (--waiting_on[d] == 0) ready.push_back(d);
  }
  std::vector<size_t> remaining;
  for (size_t k = 0; k < n; ++k)
    if (waiting_on[k] > 0) remaining.push_back(k);
  if (remaining.empty()) return;
  ReportCycles(pending, remaining, deps);
  for (size_t k : remaining) failed_parameters_.insert(spec_.parameters[pending[k]].name);
}

// One parameter: its override, its number or its expression over those resolved.
bool Compiler::ResolveParameter(const ParameterSpec& ps) {
  if (const auto o = overrides_.find(ps.name); o != overrides_.end()) {
    SetParameterValue(ps.name, o->second);
    return true;
  }
  const auto d = Value(*ps.value);
  if (d) SetParameterValue(ps.name, *d);
  return d.has_value();
}

void Compiler::SetParameterValue(const std::string& name, double value) {
  symbols_[name] = value;
  if (const auto slot = expressions_->slots().find(name); slot != expressions_->slots().end()) {
    slot_values_[slot->second] = value;
    slot_known_[slot->second] = 1;
  }
}

// Each cycle once, by its members only (not the parameters that merely use one),
// starting from its first member in the file's order.
void Compiler::ReportCycles(const std::vector<size_t>& pending, const std::vector<size_t>& remaining,
                            const std::vector<std::vector<size_t>>& deps) {
  std::vector<char> left(deps.size(), 0), done(deps.size(), 0);
  for (size_t k : remaining) left[k] = 1;
  for (size_t start : remaining) {
    if (done[start]) continue;
    std::vector<size_t> path;
    std::unordered_map<size_t, size_t> position;
    size_t cur = start;
    while (!done[cur] && !position.count(cur)) {
      position[cur] = path.size();
      path.push_back(cur);
      size_t next = cur;
      for (size_t d : deps[cur])
        if (left[d]) { next = d; break; }
      cur = next;
    }
    if (!done[cur] && position.count(cur)) {
      std::vector<size_t> cycle(path.begin() + static_cast<long>(position[cur]), path.end());
      std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
      std::vector<std::string> names;
      for (size_t k : cycle) names.push_back(spec_.parameters[pending[k]].name);
      Error("/parameters/" + EscapeToken(names.front()), "parameters defined in terms of each other: " + Join(names),
            "give at least one of them a number");
    }
    for (size_t k : path) done[k] = 1;
  }
}

}  // namespace mechkin
