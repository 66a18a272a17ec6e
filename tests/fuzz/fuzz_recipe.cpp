// libFuzzer target: the recipe reader (YAML parsing, duplicate keys, documents, every section's
// checks) on arbitrary text. Any geotandem::Error is an expected refusal; anything else (a crash, a
// sanitizer report, another exception type) is a bug.

#include <cstddef>
#include <cstdint>
#include <string>

#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/workflow/recipe.hpp"

using namespace geotandem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static workflow::PluginRegistry registry = [] {
    workflow::PluginRegistry r;
    builtin::register_attributes(r);
    return r;
  }();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)workflow::parse_recipe(text, "fuzz.yaml", registry);
  } catch (const Error&) {
  }
  return 0;
}
