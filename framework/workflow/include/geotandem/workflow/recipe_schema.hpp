#pragma once
// The recipe's own sections (input, output, execution and their nested mappings) declared with the
// parameter model the steps use (geotandem/core/params.hpp: type, default, range, unit, help), so
// that one declaration drives validation (recipe.cpp reads every section through it: unknown keys
// get a did-you-mean with their line and column), `geotandem plugins --schema-doc` and the tables of
// docs/recipe-schema.md.
//
// Adding a key to a section: one ParamSpec in recipe_schema.cpp's table (and the code that uses its
// value, in recipe.cpp or recipe_execution.cpp). A key whose default_value is empty may be left
// out; its `absent` text (RecipeSection::absent) says what happens then.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "geotandem/core/params.hpp"
#include "geotandem/workflow/registry.hpp"

namespace geotandem::workflow {

struct RecipeSection {
  std::string path; // "input", "input.synthetic", "execution.resources", ...
  std::vector<ParamSpec> keys;
  // What a key left out without a default means ("one per core ..."), for docs and help.
  std::map<std::string, std::string> absent;
  // The nested mappings (their paths), read by their own declarations.
  std::vector<std::string> sections;

  // Every key a recipe may write here: the scalar keys, then the nested sections' names.
  std::vector<std::string> key_names() const;
};

// input, input.synthetic, input.segy, output, execution, execution.resources.
const std::vector<RecipeSection>& recipe_sections();
// The section at `path`; throws std::out_of_range for an unknown path (a programming error).
const RecipeSection& recipe_section(std::string_view path);

// `document` (docs/recipe-schema.md) with every generated table replaced by the declarations': the
// lines between "<!-- generated: WHAT -->" and "<!-- end generated -->", where WHAT is a section's
// path or "step NAME" (that step's parameters, from `registry`). Everything else is kept as it is.
// Throws InvalidArgument naming an unknown WHAT or an unclosed marker.
std::string regenerate_schema_doc(const std::string& document, const PluginRegistry& registry);

// One table: | key | type | default | meaning | for `keys` (with `prefix` before each key).
std::string params_table(const std::vector<ParamSpec>& keys, const std::map<std::string, std::string>& absent = {});

} // namespace geotandem::workflow
