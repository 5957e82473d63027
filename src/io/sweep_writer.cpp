#include "io/sweep_writer.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace mechkin {

using nlohmann::json;

namespace {

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double FromJson(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

std::string Csv(double v) {
  if (std::isnan(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string Quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

// A shard field that fails validation: thrown with its JSON pointer and the problem,
// caught by MergeSweepFiles, which names the file.
struct BadField : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void Bad(const std::string& pointer, const std::string& problem) { throw BadField(pointer + ": " + problem); }

const json& Field(const json& object, const std::string& pointer, const char* key) {
  if (!object.is_object()) Bad(pointer, "expected an object");
  const auto it = object.find(key);
  if (it == object.end()) Bad(pointer + "/" + key, "missing");
  return *it;
}

// An integer in [low, high] (a float, a string or an out-of-range number is refused).
int Integer(const json& j, const std::string& pointer, long long low, long long high) {
  if (!j.is_number_integer()) Bad(pointer, "expected an integer");
  long long v = 0;
  if (j.is_number_unsigned()) v = static_cast<long long>(std::min<uint64_t>(j.get<uint64_t>(), INT64_MAX));
  else v = j.get<long long>();
  if (v < low || v > high) Bad(pointer, std::to_string(v) + " is outside " + std::to_string(low) + ".." + std::to_string(high));
  return static_cast<int>(v);
}

std::string Text(const json& j, const std::string& pointer) {
  if (!j.is_string()) Bad(pointer, "expected a string");
  return j.get<std::string>();
}

// A list of numbers (null: not a number) of exactly `size` entries.
std::vector<double> Numbers(const json& j, const std::string& pointer, size_t size, const char* per) {
  if (!j.is_array()) Bad(pointer, "expected a list of numbers");
  if (j.size() != size)
    Bad(pointer, "has " + std::to_string(j.size()) + " entries, the sweep has " + std::to_string(size) + " " + per);
  std::vector<double> out;
  out.reserve(size);
  for (size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_number() && !j[k].is_null()) Bad(pointer + "/" + std::to_string(k), "expected a number or null");
    out.push_back(FromJson(j[k]));
  }
  return out;
}

double Scalar(const json& j, const std::string& pointer) {
  if (!j.is_number() && !j.is_null()) Bad(pointer, "expected a number or null");
  return FromJson(j);
}

// Variant `j` at `pointer` of a shard of `sweep` (its parameters, columns and total read already).
VariantSummary VariantFromJson(const json& j, const std::string& pointer, const SweepResult& sweep) {
  VariantSummary v;
  v.index = Integer(Field(j, pointer, "variant"), pointer + "/variant", 0, sweep.total - 1LL);
  v.values = Numbers(Field(j, pointer, "values"), pointer + "/values", sweep.parameters.size(), "parameters");
  v.status = Text(Field(j, pointer, "status"), pointer + "/status");
  v.message = Text(Field(j, pointer, "message"), pointer + "/message");
  v.rows = Integer(Field(j, pointer, "rows"), pointer + "/rows", 0, INT32_MAX);
  v.t_stop = Scalar(Field(j, pointer, "t_stop"), pointer + "/t_stop");
  v.max_condition = Scalar(Field(j, pointer, "max_condition"), pointer + "/max_condition");
  v.t_max_condition = Scalar(Field(j, pointer, "t_max_condition"), pointer + "/t_max_condition");
  v.min = Numbers(Field(j, pointer, "min"), pointer + "/min", sweep.columns.size(), "columns");
  v.max = Numbers(Field(j, pointer, "max"), pointer + "/max", sweep.columns.size(), "columns");
  return v;
}

std::vector<std::string> Names(const json& j, const std::string& pointer) {
  if (!j.is_array()) Bad(pointer, "expected a list of names");
  std::vector<std::string> out;
  for (size_t k = 0; k < j.size(); ++k) out.push_back(Text(j[k], pointer + "/" + std::to_string(k)));
  return out;
}

// The shard's header and variants, every field validated.
SweepResult ShardFromJson(const json& doc, int* shard) {
  SweepResult part;
  part.parameters = Names(Field(doc, "", "parameters"), "/parameters");
  part.columns = Names(Field(doc, "", "columns"), "/columns");
  part.total = Integer(Field(doc, "", "total"), "/total", 0, INT32_MAX);
  part.shards = Integer(Field(doc, "", "shards"), "/shards", 1, INT32_MAX);
  *shard = Integer(Field(doc, "", "shard"), "/shard", 1, part.shards);
  if (doc.contains("sweep")) {
    if (!doc["sweep"].is_object()) Bad("/sweep", "expected an object");
    part.identity = doc["sweep"].dump();
  }
  const json& variants = Field(doc, "", "variants");
  if (!variants.is_array()) Bad("/variants", "expected a list of variants");
  for (size_t k = 0; k < variants.size(); ++k) {
    const std::string pointer = "/variants/" + std::to_string(k);
    part.variants.push_back(VariantFromJson(variants[k], pointer, part));
    if (part.variants.back().index % part.shards != *shard - 1)
      Bad(pointer + "/variant", std::to_string(part.variants.back().index) + " does not belong to shard " +
                                    std::to_string(*shard) + "/" + std::to_string(part.shards));
  }
  return part;
}

bool ReadShard(const std::string& file, json* doc, std::string* error) {
  std::ifstream in(file);
  if (!in) {
    *error = "cannot open '" + file + "'";
    return false;
  }
  try {
    *doc = json::parse(in);
    if (!doc->contains("mechkin_sweep")) throw std::runtime_error("not a sweep file");
  } catch (const std::exception& e) {
    *error = "'" + file + "' is not a sweep written with --format json (" + std::string(e.what()) + ")";
    return false;
  }
  return true;
}

// The identity keys two shards disagree on ("file differs, set differs").
std::string IdentityDifference(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return "one records its sweep, the other does not";
  const json x = json::parse(a), y = json::parse(b);
  std::string keys;
  for (const auto& [key, value] : x.items())
    if (!y.contains(key) || y.at(key) != value) keys += (keys.empty() ? "" : ", ") + key;
  for (const auto& [key, value] : y.items())
    if (!x.contains(key)) keys += (keys.empty() ? "" : ", ") + key;
  return "they differ in: " + keys;
}

// After the sort: variants 0..total-1 each exactly once (a shard edited or cut
// short names its missing or duplicated variants).
bool EveryVariantOnce(const SweepResult& merged, std::string* error) {
  std::string duplicated, missing;
  int missing_count = 0;
  size_t k = 0;
  for (int index = 0; index < merged.total; ++index) {
    int seen = 0;
    for (; k < merged.variants.size() && merged.variants[k].index == index; ++k) ++seen;
    if (seen > 1) duplicated += (duplicated.empty() ? "" : ", ") + std::to_string(index);
    if (seen == 0 && ++missing_count <= 10) missing += (missing.empty() ? "" : ", ") + std::to_string(index);
  }
  if (missing_count > 10) missing += " and " + std::to_string(missing_count - 10) + " more";
  if (duplicated.empty() && missing.empty()) return true;
  *error = !duplicated.empty() ? "variants given twice: " + duplicated : "missing variants: " + missing;
  if (!duplicated.empty() && !missing.empty()) *error += "; missing variants: " + missing;
  *error += " (of 0.." + std::to_string(merged.total - 1) + "): merge the complete, unedited shard files";
  return false;
}

}  // namespace

// The first line of an interrupted sweep's report (as a partial run table's "# PARTIAL TABLE:").
std::string PartialNote(const SweepResult& r) {
  const int share = r.total / r.shards + (r.total % r.shards > r.shard - 1 ? 1 : 0);
  return "interrupted; " + std::to_string(r.variants.size()) + " of " + std::to_string(share) +
         " variants summarised";
}

json SweepJson(const SweepResult& r) {
  json variants = json::array();
  for (const auto& v : r.variants) {
    json mins = json::array(), maxs = json::array(), values = json::array();
    for (double x : v.min) mins.push_back(Number(x));
    for (double x : v.max) maxs.push_back(Number(x));
    for (double x : v.values) values.push_back(Number(x));
    variants.push_back({{"variant", v.index}, {"values", values}, {"status", v.status}, {"message", v.message},
                        {"rows", v.rows}, {"t_stop", Number(v.t_stop)}, {"max_condition", Number(v.max_condition)},
                        {"t_max_condition", Number(v.t_max_condition)}, {"min", mins}, {"max", maxs}});
  }
  json doc = {{"mechkin_sweep", 1}, {"parameters", r.parameters}, {"columns", r.columns}, {"total", r.total},
              {"shard", r.shard}, {"shards", r.shards}, {"variants", variants}};
  if (!r.identity.empty()) doc["sweep"] = json::parse(r.identity);
  if (r.interrupted) doc["partial"] = true, doc["note"] = PartialNote(r);
  return doc;
}

std::string SweepCsv(const SweepResult& r) {
  std::ostringstream out;
  if (r.interrupted) out << "# PARTIAL SWEEP: " << PartialNote(r) << "\n";
  out << "variant";
  for (const auto& p : r.parameters) out << "," << p;
  out << ",status,rows,t_stop [s],max_condition,t_max_condition [s]";
  for (const auto& c : r.columns) out << "," << Quoted("min " + c) << "," << Quoted("max " + c);
  out << ",message\n";
  for (const auto& v : r.variants) {
    out << v.index;
    for (double x : v.values) out << "," << Csv(x);
    out << "," << v.status << "," << v.rows << "," << Csv(v.t_stop) << "," << Csv(v.max_condition) << ","
        << Csv(v.t_max_condition);
    for (size_t k = 0; k < v.min.size(); ++k) out << "," << Csv(v.min[k]) << "," << Csv(v.max[k]);
    out << "," << Quoted(v.message) << "\n";
  }
  return out.str();
}

bool MergeSweepFiles(const std::vector<std::string>& files, SweepResult* merged, std::string* error) {
  std::set<int> shards_seen;
  for (size_t f = 0; f < files.size(); ++f) {
    json doc;
    if (!ReadShard(files[f], &doc, error)) return false;
    if (doc.contains("partial") && doc["partial"] == true) {
      const std::string note = doc.contains("note") && doc["note"].is_string() ? doc["note"].get<std::string>() : "";
      *error = "'" + files[f] + "' is a partial shard (" + note + "): run that shard again to the end, then merge";
      return false;
    }
    SweepResult part;
    int shard = 0;
    try {
      part = ShardFromJson(doc, &shard);
    } catch (const BadField& e) {
      *error = "'" + files[f] + "': " + e.what() + ": the shard file is damaged; write it again with sweep --shard";
      return false;
    }
    if (f == 0) *merged = SweepResult{part.parameters, part.columns, part.total, 1, 1, {}, {}}, merged->shards = part.shards;
    if (part.parameters != merged->parameters || part.columns != merged->columns || part.total != merged->total ||
        part.shards != merged->shards) {
      *error = "'" + files[f] + "' is a shard of another sweep (parameters, columns or variant count differ)";
      return false;
    }
    if (f == 0) merged->identity = part.identity;
    if (part.identity != merged->identity) {
      *error = "'" + files[f] + "' is a shard of another sweep than '" + files[0] + "' (" +
               IdentityDifference(merged->identity, part.identity) + "): merge shards of one sweep command";
      return false;
    }
    if (!shards_seen.insert(shard).second) {
      *error = "shard " + std::to_string(shard) + " is given twice ('" + files[f] + "')";
      return false;
    }
    for (auto& v : part.variants) merged->variants.push_back(std::move(v));
  }
  std::string missing;
  for (int s = 1; s <= merged->shards; ++s)
    if (!shards_seen.count(s)) missing += (missing.empty() ? "" : ", ") + std::to_string(s) + "/" + std::to_string(merged->shards);
  if (!missing.empty()) {
    *error = "missing shards: " + missing;
    return false;
  }
  std::sort(merged->variants.begin(), merged->variants.end(),
            [](const VariantSummary& a, const VariantSummary& b) { return a.index < b.index; });
  merged->shards = 1;
  return EveryVariantOnce(*merged, error);
}

std::string SweepIdentityText(const SweepIdentity& identity) {
  std::ifstream in(identity.file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  uint64_t hash = 14695981039346656037ull;  // FNV-1a 64: an identity check, not a security one
  for (const unsigned char c : bytes.str()) hash = (hash ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  json id = {{"file_fnv1a", hex}, {"order", identity.order}, {"tolerance", identity.tolerance},
             {"solver", identity.solver}, {"set", identity.set}};
  if (identity.samples > 0) id["samples"] = {{"count", identity.samples}, {"seed", identity.seed}};
  else id["grid"] = identity.grid;
  return id.dump();
}

std::string SweepJsonText(const SweepResult& x) { return SweepJson(x).dump(1); }

}  // namespace mechkin
