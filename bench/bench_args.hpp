#pragma once
// Small command-line helpers shared by the benchmarks.

#include <sstream>
#include <string>
#include <vector>

namespace geotandem::bench {

// "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    out.push_back(item);
  return out;
}

} // namespace geotandem::bench
