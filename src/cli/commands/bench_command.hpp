// `mechkin bench FILE`: measures the speed/accuracy trade of the analysis over a
// grid of settings and recommends settings per need.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

namespace mechkin {

struct BenchCommandOptions {
  std::string file;
  bool quick = false;
  int repeats = 3;
  std::string reference;           // CSV written by `mechkin run --si`; default: computed
  std::string csv = "bench-grid.csv";
  std::string svg = "bench-front.svg";
};

void SetupBenchCommand(CLI::App& app, BenchCommandOptions* options);
int RunBenchCommand(const BenchCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
