#include "geotandem/core/suggest.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace geotandem {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Optimal string alignment distance over three rows.
  std::vector<std::size_t> prev2(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::string choice;
  for (const auto& c : candidates) {
    std::size_t d = edit_distance(word, c);
    if (d < best) {
      best = d;
      choice = c;
    }
  }
  return best <= std::max<std::size_t>(2, word.size() / 3) ? choice : std::string();
}

std::string stand_in_for(const std::string& name, const std::vector<std::string>& words) {
  const auto lower = [](std::string text) {
    for (char& c : text)
      c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
  };
  const std::string wanted = lower(name);
  for (const auto& word : words)
    if (!nearest(word, {name}).empty()) return word;
  for (const auto& word : words) {
    const std::string w = lower(word);
    const std::string& shorter = w.size() < wanted.size() ? w : wanted;
    const std::string& longer = w.size() < wanted.size() ? wanted : w;
    if (shorter.size() >= 3 && longer.compare(0, shorter.size(), shorter) == 0) return word;
  }
  return {};
}

std::string suggestion_hint(const std::string& word, const std::vector<std::string>& candidates) {
  std::string close = nearest(word, candidates);
  if (!close.empty()) return "did you mean '" + close + "'?";
  std::string list;
  for (const auto& c : candidates)
    list += (list.empty() ? "" : ", ") + c;
  return "expected one of: " + list;
}

} // namespace geotandem
