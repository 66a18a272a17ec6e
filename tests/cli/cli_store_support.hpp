#pragma once
// Helpers of the command-line tests on stores and outputs: quoting a path for the shell, a store's
// rows as `store ls --json` lists them, a file's bytes, and a small synthetic cube.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "scratch.hpp"

namespace geotandem::testing {

inline std::string q(const std::string& path) {
  return "'" + path + "'";
}

inline nlohmann::json rows_of(const std::string& store) {
  auto r = run_geotandem("store ls --json " + q(store));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::array();
}

inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// An analytic cube of 64 x 56 x 48 samples.
inline void synth(const std::string& out, int seed) {
  auto r =
      run_geotandem("-q synth --kind analytic --shape 64 56 48 --seed " + std::to_string(seed) + " --out " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

} // namespace geotandem::testing
