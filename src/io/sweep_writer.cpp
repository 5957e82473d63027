#include "io/sweep_writer.hpp"

#include <algorithm>
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

VariantSummary VariantFromJson(const json& j) {
  VariantSummary v;
  v.index = j.at("variant").get<int>();
  for (const auto& x : j.at("values")) v.values.push_back(FromJson(x));
  v.status = j.at("status").get<std::string>();
  v.message = j.at("message").get<std::string>();
  v.rows = j.at("rows").get<int>();
  v.t_stop = FromJson(j.at("t_stop"));
  v.max_condition = FromJson(j.at("max_condition"));
  v.t_max_condition = FromJson(j.at("t_max_condition"));
  for (const auto& x : j.at("min")) v.min.push_back(FromJson(x));
  for (const auto& x : j.at("max")) v.max.push_back(FromJson(x));
  return v;
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

}  // namespace

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
  return {{"mechkin_sweep", 1}, {"parameters", r.parameters}, {"columns", r.columns}, {"total", r.total},
          {"shard", r.shard}, {"shards", r.shards}, {"variants", variants}};
}

std::string SweepCsv(const SweepResult& r) {
  std::ostringstream out;
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
    try {
    SweepResult part;
    part.parameters = doc.at("parameters").get<std::vector<std::string>>();
    part.columns = doc.at("columns").get<std::vector<std::string>>();
    part.total = doc.at("total").get<int>();
    part.shards = doc.at("shards").get<int>();
    const int shard = doc.at("shard").get<int>();
    if (f == 0) *merged = SweepResult{part.parameters, part.columns, part.total, 1, 1, {}}, merged->shards = part.shards;
    if (part.parameters != merged->parameters || part.columns != merged->columns || part.total != merged->total ||
        part.shards != merged->shards) {
      *error = "'" + files[f] + "' is a shard of another sweep (parameters, columns or variant count differ)";
      return false;
    }
    if (!shards_seen.insert(shard).second) {
      *error = "shard " + std::to_string(shard) + " is given twice ('" + files[f] + "')";
      return false;
    }
    for (const auto& v : doc.at("variants")) merged->variants.push_back(VariantFromJson(v));
    } catch (const json::exception& e) {
      *error = "'" + files[f] + "' is not a complete sweep file: " + e.what();
      return false;
    }
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
  return true;
}

std::string SweepJsonText(const SweepResult& x) { return SweepJson(x).dump(1); }

}  // namespace mechkin
