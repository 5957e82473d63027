// Helpers of the importer tests: the CLI's tables and check reports as JSON, temporary
// files, and the coupler point's path compared between two runs.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "importers/importers.hpp"

namespace mechkin::import_test {

inline std::string Source(const std::string& rel) { return std::string(MECHKIN_SOURCE_DIR) + "/" + rel; }

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A file in a fresh temporary folder (one per test program run).
inline std::string TempFile(const std::string& name, const std::string& text) {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/mechkin-import-XXXXXX";
    return std::string(::mkdtemp(tmpl));
  }();
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// `mechkin ARGS`: exit code and standard output only (stderr to `err_path` when given).
inline mechkin_test::CliResult Stdout(const std::string& args, const std::string& err_path = "/dev/null") {
  return mechkin_test::RunCliWithStderr(args, err_path);
}

/// The first file's report of `mechkin check --format json ARGS`.
inline nlohmann::json CheckReport(const std::string& args) {
  const auto r = Stdout("check --format json " + args);
  const auto j = nlohmann::json::parse(r.out, nullptr, false);
  if (j.is_discarded() || !j.contains("files")) {
    ADD_FAILURE() << "check " << args << " gave no JSON report: " << r.out;
    return nlohmann::json::object();
  }
  return j["files"][0];
}

using Table = std::map<std::string, std::vector<double>>;

/// `mechkin run ARGS --si --format json`, as column name → values.
inline Table RunTable(const std::string& args) {
  const auto r = Stdout("run --si --format json " + args);
  EXPECT_EQ(r.code, 0) << "run " << args;
  const auto j = nlohmann::json::parse(r.out, nullptr, false);
  Table t;
  if (j.is_discarded()) return t;
  for (size_t c = 0; c < j["columns"].size(); ++c)
    for (const auto& row : j["rows"]) t[j["columns"][c]["name"].get<std::string>()].push_back(row[c].get<double>());
  return t;
}

struct Frame {
  double x[3];
  double R[3][3];
};

/// Body B's pose at row k (its columns B.x … B.e3).
inline Frame PoseAt(const Table& t, const std::string& b, size_t k) {
  Frame f;
  const char* xyz[] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) f.x[i] = t.at(b + xyz[i])[k];
  const double e0 = t.at(b + ".e0")[k], e1 = t.at(b + ".e1")[k], e2 = t.at(b + ".e2")[k], e3 = t.at(b + ".e3")[k];
  const double R[3][3] = {{e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)},
                          {2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1)},
                          {2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.R[i][j] = R[i][j];
  return f;
}

/// The path (global, every row) of the body point that is at `p0` in row 0.
inline std::vector<std::array<double, 3>> PointPath(const Table& t, const std::string& body, const double p0[3]) {
  const Frame f0 = PoseAt(t, body, 0);
  double local[3];
  for (int i = 0; i < 3; ++i) {
    local[i] = 0;
    for (int j = 0; j < 3; ++j) local[i] += f0.R[j][i] * (p0[j] - f0.x[j]);
  }
  std::vector<std::array<double, 3>> path;
  for (size_t k = 0; k < t.at("t").size(); ++k) {
    const Frame f = PoseAt(t, body, k);
    std::array<double, 3> p{};
    for (int i = 0; i < 3; ++i) {
      p[i] = f.x[i];
      for (int j = 0; j < 3; ++j) p[i] += f.R[i][j] * local[j];
    }
    path.push_back(p);
  }
  return path;
}

/// Largest distance between two paths of the same length (fails when the lengths differ).
inline double PathDistance(const std::vector<std::array<double, 3>>& a, const std::vector<std::array<double, 3>>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = a.size() == b.size() && !a.empty() ? 0 : INFINITY;
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    worst = std::max(worst, std::hypot(a[k][0] - b[k][0], a[k][1] - b[k][1], a[k][2] - b[k][2]));
  return worst;
}

// An .FCStd archive holding `document` as its Document.xml (and a GuiDocument.xml).
inline std::string Fcstd(const std::string& name, const std::string& document) {
  const std::string path = TempFile(name, "");
  std::remove(path.c_str());
  int code = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  EXPECT_NE(z, nullptr);
  static std::vector<std::string> keep;  // the buffers live until zip_close
  keep.push_back(document);
  keep.push_back("<?xml version='1.0'?><Document/>");
  zip_file_add(z, "Document.xml", zip_source_buffer(z, keep[keep.size() - 2].data(), keep[keep.size() - 2].size(), 0),
               ZIP_FL_OVERWRITE);
  zip_file_add(z, "GuiDocument.xml", zip_source_buffer(z, keep.back().data(), keep.back().size(), 0), ZIP_FL_OVERWRITE);
  EXPECT_EQ(zip_close(z), 0);
  return path;
}

/// Imports XML text of `format` in process.
inline importers::ImportResult Import(const std::string& text, importers::ForeignFormat format,
                                      const std::string& name = "test.xml") {
  return importers::ImportText(text, format, name);
}

/// All errors of a result as one text.
inline std::string Errors(const importers::ImportResult& r) {
  std::string s;
  for (const auto& e : r.errors) s += e.ToString() + "\n";
  return s;
}

}  // namespace mechkin::import_test
