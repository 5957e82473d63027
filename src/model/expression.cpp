#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

#include "model/time_function.hpp"

namespace mechkin {

// Recursive-descent parser. Nesting is limited so that hostile input cannot
// exhaust the stack.
class ExpressionParser {
 public:
  explicit ExpressionParser(Expression* e) : e_(e), s_(e->text_) {}

  void Run() {
    Skip();
    if (pos_ >= s_.size()) throw ExpressionError("empty expression", 1);
    e_->root_ = ParseSum(0);
    Skip();
    if (pos_ < s_.size())
      throw ExpressionError("unexpected '" + std::string(1, s_[pos_]) + "'", Col());
  }

 private:
  using Op = Expression::Op;
  static constexpr int kMaxDepth = 100;

  int Col() const { return static_cast<int>(pos_) + 1; }
  void Skip() { while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_; }
  bool Accept(char c) { Skip(); if (pos_ < s_.size() && s_[pos_] == c) { ++pos_; return true; } return false; }
  int Add(Op op, int a = -1, int b = -1, double v = 0) {
    e_->nodes_.push_back({op, v, a, b});
    return static_cast<int>(e_->nodes_.size()) - 1;
  }
  void CheckDepth(int depth) const {
    if (depth > kMaxDepth) throw ExpressionError("expression nested too deeply", Col());
  }

  int ParseSum(int depth) {
    CheckDepth(depth);
    int lhs = ParseProduct(depth + 1);
    for (;;) {
      if (Accept('+')) lhs = Add(Op::Add, lhs, ParseProduct(depth + 1));
      else if (Accept('-')) lhs = Add(Op::Sub, lhs, ParseProduct(depth + 1));
      else return lhs;
    }
  }
  int ParseProduct(int depth) {
    CheckDepth(depth);
    int lhs = ParseUnary(depth + 1);
    for (;;) {
      if (Accept('*')) lhs = Add(Op::Mul, lhs, ParseUnary(depth + 1));
      else if (Accept('/')) lhs = Add(Op::Div, lhs, ParseUnary(depth + 1));
      else return lhs;
    }
  }
  int ParseUnary(int depth) {
    CheckDepth(depth);
    if (Accept('-')) return Add(Op::Neg, ParseUnary(depth + 1));
    if (Accept('+')) return ParseUnary(depth + 1);
    return ParsePower(depth + 1);
  }
  int ParsePower(int depth) {
    CheckDepth(depth);
    int base = ParsePrimary(depth + 1);
    if (Accept('^')) return Add(Op::Pow, base, ParseUnary(depth + 1));  // right-associative
    return base;
  }
  int ParsePrimary(int depth) {
    CheckDepth(depth);
    Skip();
    if (pos_ >= s_.size()) throw ExpressionError("expression ends too early", Col());
    const char c = s_[pos_];
    if (c == '(') {
      ++pos_;
      int inner = ParseSum(depth + 1);
      if (!Accept(')')) throw ExpressionError("missing ')'", Col());
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return ParseNumber();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return ParseName(depth);
    throw ExpressionError("unexpected '" + std::string(1, c) + "'", Col());
  }
  int ParseNumber() {
    const size_t start = pos_;
    while (pos_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) ++pos_;
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      size_t p = pos_ + 1;
      if (p < s_.size() && (s_[p] == '+' || s_[p] == '-')) ++p;
      if (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) {
        pos_ = p;
        while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      }
    }
    const std::string tok = s_.substr(start, pos_ - start);
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end != tok.c_str() + tok.size() || tok == ".")
      throw ExpressionError("malformed number '" + tok + "'", static_cast<int>(start) + 1);
    if (!std::isfinite(v))
      throw ExpressionError("number '" + tok + "' is out of range", static_cast<int>(start) + 1);
    return Add(Op::Const, -1, -1, v);
  }
  int ParseName(int depth) {
    const size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    const std::string name = s_.substr(start, pos_ - start);
    const int col = static_cast<int>(start) + 1;
    if (name == "t") return Add(Op::Time);
    if (name == "pi") return Add(Op::Const, -1, -1, M_PI);
    static const std::map<std::string, Op> kFunctions = {
        {"sin", Op::Sin}, {"cos", Op::Cos}, {"tan", Op::Tan}, {"asin", Op::Asin},
        {"acos", Op::Acos}, {"atan", Op::Atan}, {"atan2", Op::Atan2}, {"exp", Op::Exp},
        {"log", Op::Log}, {"sqrt", Op::Sqrt}};
    const auto it = kFunctions.find(name);
    if (it == kFunctions.end())
      throw ExpressionError("unknown name '" + name +
                                "' (use t, pi, sin, cos, tan, asin, acos, atan, atan2, exp, log, sqrt)",
                            col);
    if (!Accept('(')) throw ExpressionError("'" + name + "' needs '(' after it", Col());
    const int a = ParseSum(depth + 1);
    int b = -1;
    if (it->second == Op::Atan2) {
      if (!Accept(',')) throw ExpressionError("atan2 takes two arguments: atan2(y, x)", Col());
      b = ParseSum(depth + 1);
    }
    if (!Accept(')')) throw ExpressionError("missing ')' after the argument of " + name, Col());
    return Add(it->second, a, b);
  }

  Expression* e_;
  const std::string& s_;
  size_t pos_ = 0;
};

Expression Expression::Parse(const std::string& text) {
  Expression e;
  e.text_ = text;
  ExpressionParser(&e).Run();
  return e;
}

Jet Expression::Eval(double t) const { return EvalNode(root_, Jet::Variable(t)); }

Jet Expression::EvalNode(int i, const Jet& t) const {
  const Node& n = nodes_[i];
  switch (n.op) {
    case Op::Const: return Jet::Constant(n.value);
    case Op::Time: return t;
    case Op::Neg: return -EvalNode(n.a, t);
    case Op::Add: return EvalNode(n.a, t) + EvalNode(n.b, t);
    case Op::Sub: return EvalNode(n.a, t) - EvalNode(n.b, t);
    case Op::Mul: return EvalNode(n.a, t) * EvalNode(n.b, t);
    case Op::Div: return EvalNode(n.a, t) / EvalNode(n.b, t);
    case Op::Pow: return Pow(EvalNode(n.a, t), EvalNode(n.b, t));
    case Op::Sin: return Sin(EvalNode(n.a, t));
    case Op::Cos: return Cos(EvalNode(n.a, t));
    case Op::Tan: return Tan(EvalNode(n.a, t));
    case Op::Asin: return Asin(EvalNode(n.a, t));
    case Op::Acos: return Acos(EvalNode(n.a, t));
    case Op::Atan: return Atan(EvalNode(n.a, t));
    case Op::Atan2: return Atan2(EvalNode(n.a, t), EvalNode(n.b, t));
    case Op::Exp: return Exp(EvalNode(n.a, t));
    case Op::Log: return Log(EvalNode(n.a, t));
    case Op::Sqrt: return Sqrt(EvalNode(n.a, t));
  }
  return Jet{};
}

Jet TimeFunction::Eval(double t) const {
  Jet j = table_ ? table_->Eval(t) : expr_->Eval(t);
  for (double& c : j.c) c *= scale_;
  return j;
}

std::string TimeFunction::Describe() const {
  return table_ ? "table" : expr_->text();
}

}  // namespace mechkin
