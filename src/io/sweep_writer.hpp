// Sweep summaries as CSV (one row per variant) and JSON (the shard format that
// `mechkin sweep --merge` joins). Numbers are written to round-trip exactly, so
// merged shards equal the unsharded sweep bit for bit.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/sweep.hpp"

namespace mechkin {

nlohmann::json SweepJson(const SweepResult& result);
/// The JSON text `sweep --format json` writes (without the final newline).
std::string SweepJsonText(const SweepResult& result);
std::string SweepCsv(const SweepResult& result);
/// What makes shards one sweep (`sweep --merge` refuses shards that differ in any).
struct SweepIdentity {
  std::string file;  // hashed (FNV-1a 64 of its bytes: another version of the file differs)
  int order = 1;
  double tolerance = 0;
  int solver = 0;
  ParameterOverrides set;         // --set
  std::vector<std::string> grid;  // --grid texts, or
  int samples = 0;                // --samples and --seed
  unsigned long seed = 1;
};
/// The identity as the JSON text SweepResult::identity holds.
std::string SweepIdentityText(const SweepIdentity& identity);
/// Joins shard files written with --format json. On failure (unreadable file,
/// shards of different sweeps, missing shards) returns false and says why,
/// naming the missing shard numbers.
bool MergeSweepFiles(const std::vector<std::string>& files, SweepResult* merged, std::string* error);

}  // namespace mechkin
