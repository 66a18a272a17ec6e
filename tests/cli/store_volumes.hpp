#pragma once
// What the command-line tests compare stores by: key -> volume of every component, read through
// `geotandem store ls --json` as a user's script would.

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "scratch.hpp"

namespace geotandem::testing {

inline std::map<std::int64_t, double> volumes_in(const std::string& store) {
  auto r = run_geotandem("store ls --json '" + store + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::map<std::int64_t, double> out;
  for (const auto& row : nlohmann::json::parse(r.out))
    out[row["key"].get<std::int64_t>()] = row["volume"].get<double>();
  return out;
}

} // namespace geotandem::testing
