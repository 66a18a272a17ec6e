#include "yaml_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "geotandem/workflow/suggest.hpp"

namespace geotandem::workflow::detail {

Where where_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0) return {};
  return {mark.line + 1, mark.column + 1};
}

InvalidArgument error_at(const std::string& file, const YAML::Node& node, const std::string& message,
                         const std::string& hint) {
  Where w = where_of(node);
  ErrorContext context{file};
  if (w.line > 0) {
    context.line = w.line;
    context.column = w.column;
  }
  return InvalidArgument(message, context, hint);
}

std::string scalar_of(const std::string& file, const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) throw error_at(file, node, what + " must be a single value, not a list or mapping");
  return node.Scalar();
}

MapReader::MapReader(std::string file, const YAML::Node& node, std::string what)
    : file_(std::move(file)), node_(node), what_(std::move(what)) {
  if (!node_.IsMap()) throw error_at(file_, node_, what_ + " must be a mapping of keys to values");
}

bool MapReader::has(const std::string& key) const {
  return static_cast<bool>(node_[key]);
}

const YAML::Node MapReader::node(const std::string& key) {
  used_.insert(key);
  return node_[key];
}

std::string MapReader::text(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  return scalar_of(file_, node(key), "'" + key + "' in " + what_);
}

std::string MapReader::required_text(const std::string& key) {
  if (!has(key)) throw error_at(file_, node_, what_ + " needs '" + key + "'");
  return text(key, {});
}

std::int64_t MapReader::integer(const std::string& key, std::int64_t fallback, std::int64_t min, std::int64_t max) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar_of(file_, n, "'" + key + "' in " + what_);
  char* end = nullptr;
  errno = 0;
  long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno) throw error_at(file_, n, "'" + key + "' is '" + s + "', not an integer");
  if (v < min || v > max)
    throw error_at(file_, n, "'" + key + "' is " + s + ", out of range",
                   "use a value between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

double MapReader::real(const std::string& key, double fallback, double min, double max) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar_of(file_, n, "'" + key + "' in " + what_);
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno || !std::isfinite(v))
    throw error_at(file_, n, "'" + key + "' is '" + s + "', not a number");
  if (v < min || v > max)
    throw error_at(file_, n, "'" + key + "' is " + s + ", out of range",
                   "use a value between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

bool MapReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar_of(file_, n, "'" + key + "' in " + what_);
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  throw error_at(file_, n, "'" + key + "' is '" + s + "', not true or false");
}

std::vector<std::string> MapReader::text_list(const std::string& key) {
  std::vector<std::string> out;
  if (!has(key)) return out;
  YAML::Node n = node(key);
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) throw error_at(file_, n, "'" + key + "' in " + what_ + " must be a name or a list of names");
  for (const auto& item : n)
    out.push_back(scalar_of(file_, item, "an item of '" + key + "'"));
  return out;
}

void MapReader::finish(const std::vector<std::string>& known) const {
  for (const auto& entry : node_) {
    std::string key = entry.first.Scalar();
    if (used_.count(key)) continue;
    bool is_known = false;
    for (const auto& k : known)
      is_known = is_known || k == key;
    if (is_known) continue;
    throw error_at(file_, entry.first, "unknown key '" + key + "' in " + what_, suggestion_hint(key, known));
  }
}

} // namespace geotandem::workflow::detail
