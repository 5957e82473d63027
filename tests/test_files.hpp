// Test helpers: the repository's mechanism files and test data as JSON or models.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/motion.hpp"
#include "model/loader.hpp"

namespace mechkin::testing_files {

/// mechanisms/NAME as JSON.
inline nlohmann::json ReadJson(const std::string& name) {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name);
  return nlohmann::json::parse(f);
}

/// tests/data/NAME as JSON.
inline nlohmann::json ReadTestData(const std::string& name) {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/" + name);
  return nlohmann::json::parse(f);
}

/// A model from a JSON document; the test fails if the loader rejects it.
inline Model FromJson(const nlohmann::json& j) {
  LoadResult r = LoadMechanismText(j.dump(), "inline");
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  return r.ok() ? std::move(*r.model) : Model{};
}

/// The rows of a motion, one vector per row.
inline std::vector<std::vector<double>> RowsOf(const Motion& m) {
  std::vector<std::vector<double>> rows(m.rows());
  for (int r = 0; r < m.rows(); ++r) rows[r].assign(&m.values()[static_cast<size_t>(r) * m.cols()], &m.values()[static_cast<size_t>(r + 1) * m.cols()]);
  return rows;
}

/// The header cells ("crank.x [m]") of a motion.
inline std::vector<std::string> HeaderOf(const Motion& m) {
  std::vector<std::string> h;
  for (const auto& c : m.columns()) h.push_back(c.Header());
  return h;
}

}  // namespace mechkin::testing_files
