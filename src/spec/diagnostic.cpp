#include "spec/diagnostic.hpp"

#include <algorithm>
#include <sstream>

namespace mechkin {

std::string Diagnostic::ToString() const {
  std::string s = (pointer.empty() ? std::string("(file)") : pointer) + ": " + message;
  if (!fix.empty()) s += " — " + fix;
  return s;
}

namespace {

// Both lists are in place order already (each is written section by section).
void MergeOne(const std::vector<Diagnostic>& a, const std::vector<long long>& a_places,
              const std::vector<Diagnostic>& b, const std::vector<long long>& b_places, std::vector<Diagnostic>* out) {
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a_places[i] <= b_places[j]))
      out->push_back(a[i++]);
    else
      out->push_back(b[j++]);
  }
}

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

void DiagnosticLog::Merge(const DiagnosticLog& first, const DiagnosticLog& second, std::vector<Diagnostic>* errors,
                           std::vector<Diagnostic>* warnings) {
  MergeOne(first.errors, first.error_places_, second.errors, second.error_places_, errors);
  MergeOne(first.warnings, first.warning_places_, second.warnings, second.warning_places_, warnings);
}

std::string EscapeToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// At most 12 names: a 10,000-body file must not turn each misspelled reference
// into a megabyte of candidates.
std::string Join(const std::vector<std::string>& v) {
  constexpr size_t kShown = 12;
  std::string s;
  for (size_t i = 0; i < v.size() && i < kShown; ++i) s += (i ? ", " : "") + v[i];
  if (v.size() > kShown) s += ", … (" + std::to_string(v.size()) + " in all)";
  return s;
}

std::string DidYouMean(const std::string& word, const std::vector<std::string>& choices) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : choices) {
    const size_t d = EditDistance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string Shorten(const std::string& s) { return s.size() > 40 ? s.substr(0, 37) + "..." : s; }

std::string FormatNumber(double t) {
  std::ostringstream o;
  o.precision(10);
  o << t;
  return o.str();
}

}  // namespace mechkin
