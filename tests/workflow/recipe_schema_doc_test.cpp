// docs/recipe-schema.md's tables are generated from the declarations recipes are validated
// against (the sections' and the built-in steps'): the committed file must be what
// `geotandem plugins --schema-doc docs/recipe-schema.md` writes.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/workflow/recipe_schema.hpp"
#include "test_paths.hpp"

namespace geotandem::workflow {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(RecipeSchemaDoc, IsUpToDate) {
  PluginRegistry registry;
  builtin::register_builtins(registry);
  const std::string path = test_paths::source() + "/docs/recipe-schema.md";
  const std::string committed = read(path);
  const std::string generated = regenerate_schema_doc(committed, registry);
  EXPECT_EQ(committed, generated) << path
                                  << " has drifted from the declarations: write it again with\n  geotandem plugins "
                                     "--schema-doc docs/recipe-schema.md > new.md && mv new.md docs/recipe-schema.md";
  // Every declared section has its table in the document.
  for (const auto& section : recipe_sections())
    EXPECT_NE(committed.find("<!-- generated: " + section.path + " -->"), std::string::npos) << section.path;
}

TEST(RecipeSchemaDoc, TablesComeFromTheDeclarations) {
  PluginRegistry registry;
  builtin::register_builtins(registry);
  const std::string doc = regenerate_schema_doc(
      "intro\n<!-- generated: execution -->\nstale\n<!-- end generated -->\n<!-- generated: step extract -->\n"
      "<!-- end generated -->\noutro\n",
      registry);
  EXPECT_EQ(doc.find("stale"), std::string::npos) << doc;
  EXPECT_NE(doc.find("| `scheduler` | `local` \\| `slurm` \\| `lsf` | `local` |"), std::string::npos) << doc;
  EXPECT_NE(doc.find("| `block_size` | integer [0, 4096], cells | `128` |"), std::string::npos) << doc;
  EXPECT_NE(doc.find("| `iso` | real | required |"), std::string::npos) << doc;
  EXPECT_EQ(doc.rfind("outro\n"), doc.size() - 6);
  EXPECT_THROW(regenerate_schema_doc("<!-- generated: nowhere -->\n<!-- end generated -->\n", registry),
               InvalidArgument);
  EXPECT_THROW(regenerate_schema_doc("<!-- generated: input -->\n", registry), InvalidArgument);
}

} // namespace
} // namespace geotandem::workflow
