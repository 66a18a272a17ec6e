#pragma once
// Typed access to a YAML mapping that remembers which keys were used, so that every unknown key
// becomes an error with its line, column and the nearest known key.

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/recipe_schema.hpp"

namespace geotandem::workflow::detail {

Where where_of(const YAML::Node& node);
// An InvalidArgument at `node` in `file`.
InvalidArgument error_at(const std::string& file, const YAML::Node& node, const std::string& message,
                         const std::string& hint = {});

// Where the nodes of a recipe's tree come from: its file, or a --set override grafted onto the
// tree. An override's value is parsed on its own, so its nodes carry positions within the value:
// an error at one of them names the --set, not a line of the file.
class RecipeSource {
public:
  explicit RecipeSource(std::string file) : file_(std::move(file)) {}
  // `key` and `value`: the nodes apply_override() put in the tree for the override `text` (a null
  // key when there is none).
  void add_override(const YAML::Node& key, const YAML::Node& value, std::string text);
  const std::string& file() const { return file_; }
  // The node's line and column in the file; none for a node of an override.
  Where where_of(const YAML::Node& node) const;
  // file:line:column, or the --set naming the value.
  ErrorContext context_of(const YAML::Node& node) const;

private:
  // The --set text of the override `node` belongs to, or null.
  const std::string* override_of(const YAML::Node& node) const;

  std::string file_;
  struct Override {
    YAML::Node key, value;
    std::string text;
  };
  std::vector<Override> overrides_;
};

// An InvalidArgument at `node`, located by `source`.
InvalidArgument error_at(const RecipeSource& source, const YAML::Node& node, const std::string& message,
                         const std::string& hint = {});
// The node's scalar text; an error naming `what` when it is not a scalar.
std::string scalar_of(const RecipeSource& source, const YAML::Node& node, const std::string& what);

// Recipes larger than this are refused (a recipe is a page of text; /dev/zero is not).
inline constexpr std::uintmax_t max_recipe_bytes = 1 << 20;

// The text of the recipe at `path`. Throws IoError for a missing or unreadable file, InvalidArgument
// for a directory, FIFO or device (which would block or never end) or a file above
// max_recipe_bytes, and for NUL bytes in the text.
std::string read_recipe_text(const std::string& path);

// Parses `text` (named `file` in messages) as exactly one YAML document. InvalidArgument, with line
// and column, for invalid YAML, a second document, a key given twice in one mapping (naming both
// lines) and a scalar holding a control character (other than tab and newline).
YAML::Node load_single_document(const std::string& text, const std::string& file);

class MapReader {
public:
  // `what` names the mapping in messages ("input", "step 2 (extract)"). `source` outlives the reader.
  MapReader(const RecipeSource& source, const YAML::Node& node, std::string what);

  bool has(const std::string& key) const;
  void rename(std::string what) { what_ = std::move(what); }
  const YAML::Node node(const std::string& key);
  std::string text(const std::string& key, const std::string& fallback);
  std::string required_text(const std::string& key);
  // The scalar text of the value of `key` (present): an error at the key when it has no value
  // (`key:` alone), at the value when it is a list or a mapping.
  std::string scalar(const std::string& key);
  std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t min, std::int64_t max);
  double real(const std::string& key, double fallback, double min, double max);
  bool boolean(const std::string& key, bool fallback);
  std::vector<std::string> text_list(const std::string& key);

  // The error for the required key `key`, missing here: placed at an unknown key that looks like it
  // ("needs 'iso'; is 'isovalue' (line 7) meant to be it?", with "did you mean 'iso'?") when there is
  // one, else at the mapping with `hint`. Unknown: not read by any getter and not in `known`.
  [[noreturn]] void missing(const std::string& key, const std::vector<std::string>& known,
                            const std::string& hint = {}) const;

  // Keys not consumed by any getter are errors: "unknown key 'x' in <what>" with a suggestion from
  // `known` (the keys the getters may read).
  void finish(const std::vector<std::string>& known) const;

  const RecipeSource& source() const { return source_; }
  const YAML::Node& map() const { return node_; }

private:
  const RecipeSource& source_;
  YAML::Node node_;
  std::string what_;
  std::set<std::string> used_;
};

// The keys `section` declares, read from `m`: each one given, checked by its declaration (an error
// at its value's line and column), else its default; a key left out without a default is absent
// from the result. List keys (ParamSpec::list) are left to the caller, which reads them from `m`.
// Does not call finish(): the caller reads the nested sections first, then
// m.finish(section.key_names()).
ParamValues read_section(MapReader& m, const RecipeSection& section);
// The entries of the list key `spec` (declared with `list`), each checked against spec.entry() and
// their count against spec.list_length; an error at the entry's line and column ("parameter
// 'shape[1]' is 8, out of range"). Empty when the key is absent; a scalar is a one-entry list when
// the length is free.
std::vector<ParamValue> read_list(MapReader& m, const ParamSpec& spec, const std::string& section);

} // namespace geotandem::workflow::detail
