#include "model/expression_cache.hpp"

#include "spec/spec.hpp"

namespace mechkin {

ExpressionCache::ExpressionCache(const MechanismSpec& spec) : spec_(&spec) {
  for (const ParameterSpec& p : spec.parameters) slots_.emplace(p.name, static_cast<int>(slots_.size()));
}

const ExpressionCache::Constant* ExpressionCache::FindConstant(const std::string* text) const {
  const auto it = constants_.find(text);
  return it == constants_.end() ? nullptr : &it->second;
}

std::shared_ptr<const Expression> ExpressionCache::FindTimeFunction(const std::string* text) const {
  const auto it = time_functions_.find(text);
  return it == time_functions_.end() ? nullptr : it->second;
}

const std::vector<std::string>* ExpressionCache::FindNames(const std::string* text) const {
  const auto it = names_.find(text);
  return it == names_.end() ? nullptr : &it->second;
}

const ExpressionCache::Constant* ExpressionCache::RecordConstant(const std::string* text, Expression expression) {
  std::vector<int> used = expression.SlotsUsed();
  return &constants_.insert_or_assign(text, Constant{std::move(expression), std::move(used)}).first->second;
}

void ExpressionCache::RecordTimeFunction(const std::string* text, std::shared_ptr<const Expression> expression) {
  time_functions_[text] = std::move(expression);
}

const std::vector<std::string>& ExpressionCache::RecordNames(const std::string* text) {
  return names_.insert_or_assign(text, Expression::Names(*text)).first->second;
}

}  // namespace mechkin
