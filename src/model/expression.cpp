#include <cctype>
#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>

#include "model/time_function.hpp"

namespace mechkin {

// Recursive-descent parser. Nesting is limited so that hostile input cannot
// exhaust the stack.
namespace {

bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// End of the name starting at `start`; with `dotted`, one ".component" (a letter
// after the dot) belongs to it: "tip.x" names an output's coordinate.
size_t NameEnd(const std::string& s, size_t start, bool dotted) {
  size_t pos = start;
  while (pos < s.size() && IsNameChar(s[pos])) ++pos;
  if (dotted && pos + 1 < s.size() && s[pos] == '.' && std::isalpha(static_cast<unsigned char>(s[pos + 1]))) {
    ++pos;
    while (pos < s.size() && IsNameChar(s[pos])) ++pos;
  }
  return pos;
}

// End of the number token starting at `start`: digits and dots, then an exponent
// (e, an optional sign, digits) when one follows.
size_t NumberEnd(const std::string& s, size_t start) {
  size_t pos = start;
  while (pos < s.size() && (IsDigit(s[pos]) || s[pos] == '.')) ++pos;
  if (pos < s.size() && (s[pos] == 'e' || s[pos] == 'E')) {
    size_t p = pos + 1;
    if (p < s.size() && (s[p] == '+' || s[p] == '-')) ++p;
    if (p < s.size() && IsDigit(s[p])) {
      pos = p;
      while (pos < s.size() && IsDigit(s[pos])) ++pos;
    }
  }
  return pos;
}

}  // namespace

class ExpressionParser {
 public:
  ExpressionParser(Expression* e, const ExpressionSymbols* symbols, bool allow_time,
                   const ExpressionSlots* slots = nullptr, bool dotted_names = false)
      : e_(e), s_(e->text_), symbols_(symbols), slots_(slots), allow_time_(allow_time), dotted_(dotted_names) {}

  static const std::map<std::string, Expression::Op>& Functions() {
    static const std::map<std::string, Op> kFunctions = {
        {"sin", Op::Sin}, {"cos", Op::Cos}, {"tan", Op::Tan}, {"asin", Op::Asin},
        {"acos", Op::Acos}, {"atan", Op::Atan}, {"atan2", Op::Atan2}, {"exp", Op::Exp},
        {"log", Op::Log}, {"sqrt", Op::Sqrt}};
    return kFunctions;
  }

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
  // Each level of parentheses or of a function call costs 5 levels of the
  // recursive descent (sum, product, unary, power, primary): 325 allows 64.
  static constexpr int kMaxDepth = 5 * Expression::kMaxNesting + 5;

  int Col() const { return static_cast<int>(pos_) + 1; }
  void Skip() { while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_; }
  bool Accept(char c) { Skip(); if (pos_ < s_.size() && s_[pos_] == c) { ++pos_; return true; } return false; }
  int Add(Op op, int a = -1, int b = -1, double v = 0) {
    e_->nodes_.push_back({op, v, a, b});
    return static_cast<int>(e_->nodes_.size()) - 1;
  }
  void CheckDepth(int depth) const {
    if (depth > kMaxDepth)
      throw ExpressionError("expression nested too deeply (at most " + std::to_string(Expression::kMaxNesting) +
                                " levels of parentheses, function calls, signs and powers)",
                            Col());
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
    throw ExpressionError(UnexpectedCharacter(), Col());
  }
  // "unexpected '×'": non-ASCII look-alikes get their ASCII replacement named.
  std::string UnexpectedCharacter() const {
    const unsigned char c = static_cast<unsigned char>(s_[pos_]);
    if (c < 0x80) return "unexpected '" + std::string(1, static_cast<char>(c)) + "'";
    static const std::pair<const char*, const char*> kLookAlikes[] = {
        {"\xe2\x88\x92", "'-' (the text has a Unicode minus sign U+2212)"},
        {"\xe2\x80\x93", "'-' (the text has an en dash U+2013)"},
        {"\xc3\x97", "'*' (the text has a multiplication sign U+00D7)"},
        {"\xc2\xb7", "'*' (the text has a middle dot U+00B7)"},
        {"\xc3\xb7", "'/' (the text has a division sign U+00F7)"},
        {"\xc2\xa0", "a plain space (the text has a non-breaking space U+00A0)"},
        {"\xcf\x80", "'pi' (the text has the Greek letter U+03C0)"}};
    for (const auto& [bytes, fix] : kLookAlikes)
      if (s_.compare(pos_, std::strlen(bytes), bytes) == 0) return std::string("non-ASCII character: use ") + fix;
    return "non-ASCII character (byte 0x" + Hex(c) + "): expressions use ASCII only";
  }
  static std::string Hex(unsigned char c) {
    const char* digits = "0123456789abcdef";
    return {digits[c >> 4], digits[c & 15]};
  }
  int ParseNumber() {
    const size_t start = pos_;
    pos_ = NumberEnd(s_, pos_);
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
    pos_ = NameEnd(s_, pos_, dotted_);
    const std::string name = s_.substr(start, pos_ - start);
    const int col = static_cast<int>(start) + 1;
    if (name == "t") {
      if (!allow_time_)
        throw ExpressionError("'t' is not allowed here: geometry and parameters are constants", col);
      return Add(Op::Time);
    }
    if (name == "pi") return Add(Op::Const, -1, -1, M_PI);
    if (symbols_) {
      const auto sym = symbols_->find(name);
      if (sym != symbols_->end()) return Add(Op::Const, -1, -1, sym->second);
    }
    if (slots_) {
      const auto slot = slots_->find(name);
      if (slot != slots_->end()) return Add(Op::Slot, slot->second);
    }
    const auto it = Functions().find(name);
    if (it == Functions().end())
      throw ExpressionError("unknown name '" + name + "' (use " + (allow_time_ ? "t, " : "") +
                                ((symbols_ && !symbols_->empty()) || (slots_ && !slots_->empty()) ? "the parameters, " : "") +
                                "pi, sin, cos, tan, asin, acos, atan, atan2, exp, log, sqrt)",
                            col, name);
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
  const ExpressionSymbols* symbols_;
  const ExpressionSlots* slots_;
  bool allow_time_;
  bool dotted_;  // names may have one ".component" (an output's coordinate: "tip.x")
  size_t pos_ = 0;
};

bool Expression::IsReservedName(const std::string& name) {
  return name == "t" || name == "pi" || ExpressionParser::Functions().count(name) > 0;
}

namespace {

// The names of a text by scanning alone (no parse, no exception), the reserved ones left out.
std::vector<std::string> ScanNames(const std::string& text, bool dotted) {
  std::vector<std::string> names;
  for (size_t i = 0; i < text.size();) {
    if (IsDigit(text[i]) || text[i] == '.') {
      i = NumberEnd(text, i);
    } else if (IsNameChar(text[i])) {
      const size_t end = NameEnd(text, i, dotted);
      std::string name = text.substr(i, end - i);
      if (!Expression::IsReservedName(name)) names.push_back(std::move(name));
      i = end;
    } else {
      ++i;
    }
  }
  return names;
}

}  // namespace

std::vector<std::string> Expression::Names(const std::string& text) { return ScanNames(text, false); }

std::vector<std::string> Expression::DottedNames(const std::string& text) { return ScanNames(text, true); }

Expression Expression::Parse(const std::string& text, const ExpressionSymbols* symbols, bool allow_time) {
  if (text.size() > kMaxLength)
    throw ExpressionError("expression is longer than " + std::to_string(kMaxLength) + " characters (" +
                              std::to_string(text.size()) + ")",
                          static_cast<int>(kMaxLength));
  Expression e;
  e.text_ = text;
  ExpressionParser(&e, symbols, allow_time).Run();
  return e;
}

Expression Expression::ParseWithSlots(const std::string& text, const ExpressionSlots& slots, bool allow_time) {
  if (text.size() > kMaxLength) return Parse(text, nullptr, allow_time);  // throws the length error
  Expression e;
  e.text_ = text;
  ExpressionParser(&e, nullptr, allow_time, &slots).Run();
  return e;
}

Expression Expression::ParseOverColumns(const std::string& text, const ExpressionSymbols& symbols,
                                        const ExpressionSlots& slots) {
  if (text.size() > kMaxLength) return Parse(text, nullptr, true);  // throws the length error
  Expression e;
  e.text_ = text;
  ExpressionParser(&e, &symbols, true, &slots, true).Run();
  return e;
}

std::vector<int> Expression::SlotsUsed() const {
  std::vector<int> used;
  for (const Node& n : nodes_)
    if (n.op == Op::Slot && std::find(used.begin(), used.end(), n.a) == used.end()) used.push_back(n.a);
  return used;
}

namespace {

// Value-only arithmetic for the extended-precision evaluation, named like the jet
// functions so that one node evaluator serves both.
long double Pow(long double a, long double b) { return std::pow(a, b); }
long double Sin(long double a) { return std::sin(a); }
long double Cos(long double a) { return std::cos(a); }
long double Tan(long double a) { return std::tan(a); }
long double Asin(long double a) { return std::asin(a); }
long double Acos(long double a) { return std::acos(a); }
long double Atan(long double a) { return std::atan(a); }
long double Atan2(long double y, long double x) { return std::atan2(y, x); }
long double Exp(long double a) { return std::exp(a); }
long double Log(long double a) { return std::log(a); }
long double Sqrt(long double a) { return std::sqrt(a); }
template <typename V> V ConstantOf(double c);
template <> Jet ConstantOf<Jet>(double c) { return Jet::Constant(c); }
template <> long double ConstantOf<long double>(double c) { return c; }

}  // namespace

template <typename V>
V Expression::EvalNode(const Node& n, const V& t, const std::vector<V>& v) {
  switch (n.op) {
    case Op::Const: return ConstantOf<V>(n.value);
    case Op::Time: return t;
    case Op::Slot: return ConstantOf<V>(std::numeric_limits<double>::quiet_NaN());  // EvalWithSlots values them
    case Op::Neg: return -v[n.a];
    case Op::Add: return v[n.a] + v[n.b];
    case Op::Sub: return v[n.a] - v[n.b];
    case Op::Mul: return v[n.a] * v[n.b];
    case Op::Div: return v[n.a] / v[n.b];
    case Op::Pow: return Pow(v[n.a], v[n.b]);
    case Op::Sin: return Sin(v[n.a]);
    case Op::Cos: return Cos(v[n.a]);
    case Op::Tan: return Tan(v[n.a]);
    case Op::Asin: return Asin(v[n.a]);
    case Op::Acos: return Acos(v[n.a]);
    case Op::Atan: return Atan(v[n.a]);
    case Op::Atan2: return Atan2(v[n.a], v[n.b]);
    case Op::Exp: return Exp(v[n.a]);
    case Op::Log: return Log(v[n.a]);
    case Op::Sqrt: return Sqrt(v[n.a]);
  }
  return V{};
}

// Nodes are stored children first (the parser adds a node after its operands),
// so one pass in index order evaluates the tree without recursion: no stack
// depth grows with the length of the expression.
Jet Expression::Eval(double t) const {
  thread_local std::vector<Jet> value;
  value.resize(nodes_.size());
  const Jet time = Jet::Variable(t);
  for (size_t i = 0; i < nodes_.size(); ++i) value[i] = EvalNode(nodes_[i], time, value);
  return value[root_];
}

Jet Expression::EvalWithSlots(double t, const std::vector<double>& slot_values) const {
  thread_local std::vector<Jet> value;
  value.resize(nodes_.size());
  const Jet time = Jet::Variable(t);
  for (size_t i = 0; i < nodes_.size(); ++i)
    value[i] = nodes_[i].op == Op::Slot ? Jet::Constant(slot_values[nodes_[i].a]) : EvalNode(nodes_[i], time, value);
  return value[root_];
}

Jet Expression::EvalWithSlotJets(double t, const std::vector<Jet>& slot_jets) const {
  thread_local std::vector<Jet> value;
  value.resize(nodes_.size());
  const Jet time = Jet::Variable(t);
  for (size_t i = 0; i < nodes_.size(); ++i)
    value[i] = nodes_[i].op == Op::Slot ? slot_jets[nodes_[i].a] : EvalNode(nodes_[i], time, value);
  return value[root_];
}

long double Expression::ValueExtended(double t) const {
  thread_local std::vector<long double> value;
  value.resize(nodes_.size());
  const long double time = t;
  for (size_t i = 0; i < nodes_.size(); ++i) value[i] = EvalNode(nodes_[i], time, value);
  return value[root_];
}

long double TimeFunction::ValueExtended(double t) const {
  const long double v = table_ ? static_cast<long double>(table_->Eval(t).c[0]) : expr_->ValueExtended(t);
  if (!std::isfinite(v)) return static_cast<long double>(Eval(t).c[0]);
  return v * static_cast<long double>(scale_);
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
