#include "cli/commands/check_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "analysis/enum_names.hpp"
#include "cli/commands/load_for_command.hpp"
#include "io/check_formats.hpp"

namespace mechkin {

namespace {

constexpr size_t kSlowestShown = 5;

// The paths of a list, one a line (empty lines skipped, a trailing CR dropped).
bool ReadList(const std::string& list, std::vector<std::string>* files, std::ostream& err) {
  std::ifstream file;
  if (list != "-") {
    file.open(list);
    if (!file) {
      err << "mechkin check: --files-from: cannot read '" << list << "'\n";
      return false;
    }
  }
  std::istream& in = list == "-" ? std::cin : file;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line == "-" && list == "-") {
      err << "mechkin check: --files-from -: the list is the standard input, so it cannot name '-'\n";
      return false;
    }
    files->push_back(line);
  }
  return true;
}

bool CheckOutputOptions(const CheckOptions& o, std::ostream& err) {
  if (!o.output.empty() && o.format != "jsonl") {
    err << "mechkin check: -o writes JSON lines: add --format jsonl (or redirect the standard output)\n";
    return false;
  }
  if (o.resume && (o.output.empty() || o.output == "-")) {
    err << "mechkin check: --resume reads the output of an earlier run: give it with -o OUT\n";
    return false;
  }
  return true;
}

}  // namespace

bool PlanCheck(const CheckOptions& o, CheckPlan* plan, std::ostream& err) {
  if (!CheckOutputOptions(o, err)) return false;
  std::vector<std::string> files = o.files;
  if (!o.files_from.empty() && !ReadList(o.files_from, &files, err)) return false;
  plan->listed = files.size();
  plan->summary = files.size() > 1 || !o.files_from.empty() || !o.output.empty();
  int shard = 1, shards = 1;
  if (!o.shard.empty() && !ParseShardText(o.shard, &shard, &shards)) {
    err << "mechkin check: --shard '" << o.shard << "': expected i/N with 1 <= i <= N, e.g. --shard 2/8\n";
    return false;
  }
  CheckLines done;
  std::string error;
  if (o.resume && !ReadCheckLines(o.output, &done, &error)) {
    err << "mechkin check: --resume: " << error << "; give another -o, or remove the line\n";
    return false;
  }
  plan->keep_bytes = done.complete_bytes;
  for (size_t k = 0; k < files.size(); ++k) {
    if (static_cast<int>(k % static_cast<size_t>(shards)) != shard - 1) continue;
    const auto it = done.verdicts.find(files[k]);
    if (it == done.verdicts.end()) plan->files.push_back(files[k]);
    else plan->resumed.insert(*it);
  }
  return true;
}

CheckTally::CheckTally(const CheckPlan& plan) : start_(std::chrono::steady_clock::now()) {
  for (const auto& [file, verdict] : plan.resumed) {
    ++resumed_counts_[verdict];
    exit_code_ = std::max(exit_code_, ExitCodeOf(verdict));
  }
}

void CheckTally::Add(const std::string& file, const FileCheck& check) {
  ++checked_;
  ++counts_[check.verdict];
  exit_code_ = std::max(exit_code_, ExitCodeOf(check.verdict));
  slowest_.emplace_back(check.seconds, file);
  std::sort(slowest_.begin(), slowest_.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (slowest_.size() > kSlowestShown) slowest_.pop_back();
}

int CheckTally::ExitCode() const { return exit_code_; }

namespace {

void PrintCounts(const std::map<CheckVerdict, size_t>& counts, std::ostream& err) {
  bool first = true;
  for (const auto& [verdict, n] : counts) {
    err << (first ? "" : ", ") << n << " " << ToString(verdict);
    first = false;
  }
  if (first) err << "none";
}

}  // namespace

void CheckTally::PrintSummary(int jobs, std::ostream& err) const {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  err << std::fixed << std::setprecision(2) << "mechkin check: " << checked_ << (checked_ == 1 ? " file" : " files")
      << " in " << seconds << " s (" << std::setprecision(1) << (seconds > 0 ? checked_ / seconds : 0.0)
      << " files/s, " << jobs << (jobs == 1 ? " job" : " jobs") << "): ";
  PrintCounts(counts_, err);
  err << "\n";
  size_t resumed = 0;
  for (const auto& kv : resumed_counts_) resumed += kv.second;
  if (resumed > 0) {
    err << "  resumed: " << resumed << " files already in the output (";
    PrintCounts(resumed_counts_, err);
    err << "), not checked again\n";
  }
  if (slowest_.empty()) return;
  err << "  slowest:";
  for (size_t k = 0; k < slowest_.size(); ++k)
    err << (k ? "," : "") << " " << slowest_[k].second << " " << std::setprecision(3) << slowest_[k].first << " s";
  err << "\n";
  err.unsetf(std::ios::floatfield);
  err << std::setprecision(6);
}

}  // namespace mechkin
