#include "yaml_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <yaml-cpp/eventhandler.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "geotandem/workflow/suggest.hpp"

namespace geotandem::workflow::detail {

std::string read_recipe_text(const std::string& path) {
  std::error_code ec;
  auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw IoError("cannot read the recipe: no such file", {path}, "check the path");
  if (!std::filesystem::is_regular_file(status))
    throw InvalidArgument(std::filesystem::is_directory(status)
                              ? "the recipe is a directory, not a file"
                              : "the recipe is not a regular file (a FIFO or a device)",
                          {path}, "give the path of a recipe file (.yaml)");
  auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_recipe_bytes)
    throw InvalidArgument("the recipe has " + std::to_string(size) + " bytes; recipes are limited to " +
                              std::to_string(max_recipe_bytes) + " bytes",
                          {path}, "is this the right file?");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read the recipe", {path}, "check its permissions");
  std::string text;
  text.resize(max_recipe_bytes + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max_recipe_bytes)
    throw InvalidArgument("the recipe is longer than " + std::to_string(max_recipe_bytes) + " bytes", {path},
                          "is this the right file?");
  if (auto nul = text.find('\0'); nul != std::string::npos) {
    long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n'));
    throw InvalidArgument("the recipe holds a NUL byte", {path, line}, "a recipe is YAML text");
  }
  return text;
}

namespace {

// Bounds on the walk: aliases can make a cycle (&a [*a]) or an exponential tree (nested lists of
// aliases); a recipe is a few hundred nodes.
constexpr int max_depth = 64;
constexpr long max_nodes = 100000;

void check_node(const std::string& file, const YAML::Node& node, int depth, long& visited) {
  if (depth > max_depth || ++visited > max_nodes)
    throw error_at(file, node,
                   depth > max_depth ? "the recipe nests deeper than " + std::to_string(max_depth) + " levels"
                                     : "the recipe expands to more than " + std::to_string(max_nodes) + " values",
                   "is an alias (*name) referring to itself, or to lists of aliases?");
  if (node.IsScalar()) {
    for (unsigned char c : node.Scalar())
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f) {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02X", c);
        throw error_at(file, node, std::string("control character ") + code + " in '" + node.Scalar() + "'",
                       "paths and names may not hold control characters");
      }
  } else if (node.IsSequence()) {
    for (const auto& item : node)
      check_node(file, item, depth + 1, visited);
  } else if (node.IsMap()) {
    std::map<std::string, YAML::Node> seen;
    for (const auto& entry : node) {
      check_node(file, entry.first, depth + 1, visited);
      check_node(file, entry.second, depth + 1, visited);
      if (!entry.first.IsScalar()) continue;
      auto [it, fresh] = seen.emplace(entry.first.Scalar(), entry.first);
      if (!fresh)
        throw error_at(file, entry.first,
                       "key '" + entry.first.Scalar() + "' is given twice (lines " +
                           std::to_string(it->second.Mark().line + 1) + " and " +
                           std::to_string(entry.first.Mark().line + 1) + ")",
                       "keep one of them");
    }
  }
}

} // namespace

// Receives a document's parse events and keeps only where the document starts.
class DocumentStart final : public YAML::EventHandler {
public:
  YAML::Mark mark;
  void OnDocumentStart(const YAML::Mark& m) override { mark = m; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

YAML::Node load_single_document(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
    // A second document: the parser is asked for two documents at most (YAML::LoadAll can loop
    // without end on some malformed input).
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentStart first, second;
    if (parser.HandleNextDocument(first) && parser.HandleNextDocument(second))
      throw InvalidArgument("the recipe holds a second YAML document", {file, second.mark.line + 1},
                            "a recipe is one document: remove the '---' line and what follows, or split the file");
  } catch (const YAML::ParserException& e) {
    throw InvalidArgument("not valid YAML: " + e.msg, {file, e.mark.line + 1, e.mark.column + 1},
                          "check indentation and the ':' after each key");
  }
  long visited = 0;
  check_node(file, root, 0, visited);
  return root;
}

Where where_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0) return {};
  return {mark.line + 1, mark.column + 1};
}

namespace {
// `file`, with the node's line and column when it has them.
ErrorContext context_in(const std::string& file, const YAML::Node& node) {
  const Where w = where_of(node);
  ErrorContext context{file};
  if (w.line > 0) {
    context.line = w.line;
    context.column = w.column;
  }
  return context;
}
} // namespace

InvalidArgument error_at(const std::string& file, const YAML::Node& node, const std::string& message,
                         const std::string& hint) {
  return InvalidArgument(message, context_in(file, node), hint);
}

namespace {
// Whether `node` is `root` or inside it (aliases in a recipe are bounded by check_node).
bool contains(const YAML::Node& root, const YAML::Node& node, int depth = 0) {
  if (root.is(node)) return true;
  if (depth > max_depth) return false;
  if (root.IsSequence()) {
    for (const auto& item : root)
      if (contains(item, node, depth + 1)) return true;
  } else if (root.IsMap()) {
    for (const auto& entry : root)
      if (contains(entry.first, node, depth + 1) || contains(entry.second, node, depth + 1)) return true;
  }
  return false;
}
} // namespace

void RecipeSource::add_override(const YAML::Node& key, const YAML::Node& value, std::string text) {
  overrides_.push_back({key, value, std::move(text)});
}

const std::string* RecipeSource::override_of(const YAML::Node& node) const {
  // The last override of a key replaced any earlier one's value: search from the last.
  for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it)
    if ((!it->key.IsNull() && it->key.is(node)) || contains(it->value, node)) return &it->text;
  return nullptr;
}

Where RecipeSource::where_of(const YAML::Node& node) const {
  if (override_of(node)) return {};
  return detail::where_of(node);
}

ErrorContext RecipeSource::context_of(const YAML::Node& node) const {
  if (const std::string* text = override_of(node)) return ErrorContext{"--set " + *text};
  return context_in(file_, node);
}

InvalidArgument error_at(const RecipeSource& source, const YAML::Node& node, const std::string& message,
                         const std::string& hint) {
  return InvalidArgument(message, source.context_of(node), hint);
}

std::string scalar_of(const RecipeSource& source, const YAML::Node& node, const std::string& what) {
  // `key:` with nothing after it is null in YAML: say that the value is missing, not that it is a list.
  if (node.IsNull())
    throw error_at(source, node, what + " has no value", "give it a value after the colon, or leave the key out");
  if (!node.IsScalar()) throw error_at(source, node, what + " must be a single value, not a list or mapping");
  return node.Scalar();
}

MapReader::MapReader(const RecipeSource& source, const YAML::Node& node, std::string what)
    : source_(source), node_(node), what_(std::move(what)) {
  if (!node_.IsMap()) throw error_at(source_, node_, what_ + " must be a mapping of keys to values");
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
  return scalar(key);
}

std::string MapReader::scalar(const std::string& key) {
  YAML::Node value = node(key);
  // A null value's mark is where the next token starts (often the next line): name the key's place.
  if (value.IsNull())
    for (const auto& entry : node_)
      if (entry.first.IsScalar() && entry.first.Scalar() == key)
        throw error_at(source_, entry.first, "'" + key + "' in " + what_ + " has no value",
                       "give it a value after the colon, or leave the key out");
  return scalar_of(source_, value, "'" + key + "' in " + what_);
}

std::string MapReader::required_text(const std::string& key) {
  if (!has(key)) missing(key, {key});
  return text(key, {});
}

void MapReader::missing(const std::string& key, const std::vector<std::string>& known, const std::string& hint) const {
  std::vector<std::string> unknown;
  std::vector<YAML::Node> nodes;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) continue;
    const std::string& k = entry.first.Scalar();
    if (used_.count(k) || std::find(known.begin(), known.end(), k) != known.end()) continue;
    unknown.push_back(k);
    nodes.push_back(entry.first);
  }
  const std::string meant = stand_in_for(key, unknown);
  if (meant.empty()) throw error_at(source_, node_, what_ + " needs '" + key + "'", hint);
  const YAML::Node& at =
      nodes[static_cast<std::size_t>(std::find(unknown.begin(), unknown.end(), meant) - unknown.begin())];
  throw error_at(source_, at, what_ + " needs '" + key + "', and has an unknown key '" + meant + "' instead",
                 "did you mean '" + key + "'? rename '" + meant + "' to '" + key + "'" +
                     (hint.empty() ? std::string() : "; " + hint));
}

std::int64_t MapReader::integer(const std::string& key, std::int64_t fallback, std::int64_t min, std::int64_t max) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar(key);
  char* end = nullptr;
  errno = 0;
  long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno) throw error_at(source_, n, "'" + key + "' is '" + s + "', not an integer");
  if (v < min || v > max)
    throw error_at(source_, n, "'" + key + "' is " + s + ", out of range",
                   "use a value between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

double MapReader::real(const std::string& key, double fallback, double min, double max) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar(key);
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno || !std::isfinite(v))
    throw error_at(source_, n, "'" + key + "' is '" + s + "', not a number");
  if (v < min || v > max)
    throw error_at(source_, n, "'" + key + "' is " + s + ", out of range",
                   "use a value between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

bool MapReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  YAML::Node n = node(key);
  std::string s = scalar(key);
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  throw error_at(source_, n, "'" + key + "' is '" + s + "', not true or false");
}

std::vector<std::string> MapReader::text_list(const std::string& key) {
  std::vector<std::string> out;
  if (!has(key)) return out;
  YAML::Node n = node(key);
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) throw error_at(source_, n, "'" + key + "' in " + what_ + " must be a name or a list of names");
  for (const auto& item : n)
    out.push_back(scalar_of(source_, item, "an item of '" + key + "'"));
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
    // A key that begins with a known one ('isovalue' for 'iso') is no typo by edit distance.
    std::string hint = suggestion_hint(key, known);
    if (nearest(key, known).empty())
      if (const std::string meant = stand_in_for(key, known); !meant.empty()) hint = "did you mean '" + meant + "'?";
    throw error_at(source_, entry.first, "unknown key '" + key + "' in " + what_, hint);
  }
}

ParamValues read_section(MapReader& m, const RecipeSection& section) {
  ParamValues values;
  for (const ParamSpec& spec : section.keys) {
    if (spec.list) continue;
    if (!m.has(spec.name)) {
      if (spec.default_value) values[spec.name] = parse_param(spec, *spec.default_value);
      continue;
    }
    const YAML::Node at = m.node(spec.name);
    const std::string text = m.scalar(spec.name);
    try {
      values[spec.name] = parse_param(spec, text, section.path);
    } catch (const Error& e) {
      throw error_at(m.source(), at, e.message(), e.hint());
    }
  }
  return values;
}

std::vector<ParamValue> read_list(MapReader& m, const ParamSpec& spec, const std::string& section) {
  std::vector<ParamValue> values;
  if (!m.has(spec.name)) return values;
  const YAML::Node list = m.node(spec.name);
  const std::string count = spec.list_length ? std::to_string(spec.list_length) + " " : std::string();
  if (!(list.IsSequence() || (list.IsScalar() && spec.list_length <= 1)) ||
      (spec.list_length && list.size() != spec.list_length))
    throw error_at(m.source(), list, section + ": '" + spec.name + "' must be " + spec.valid_values(), spec.help);
  const auto entry = [&](const YAML::Node& node, std::size_t i) {
    ParamSpec e = spec.entry();
    e.name = spec.name + "[" + std::to_string(i) + "]";
    const std::string text = scalar_of(m.source(), node, "entry " + std::to_string(i) + " of '" + spec.name + "'");
    try {
      values.push_back(parse_param(e, text, section));
    } catch (const Error& err) {
      throw error_at(m.source(), node, err.message(), err.hint());
    }
  };
  if (list.IsScalar()) {
    entry(list, 0);
    return values;
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    entry(list[i], i);
  return values;
}

} // namespace geotandem::workflow::detail
