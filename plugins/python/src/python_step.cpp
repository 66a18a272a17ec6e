// The `python` step: its declarations, its checks (the function is imported when the recipe is
// validated, so an unimportable module is a validation error at the recipe's line) and the lazy
// attribute it builds.

#include <charconv>
#include <regex>

#include "geotandem/core/error.hpp"
#include "geotandem/python_step/register.hpp"
#include "geotandem/workflow/builtin_steps.hpp"
#include "python_attribute.hpp"

namespace geotandem::python_step {
namespace {

constexpr std::int64_t max_halo = 1000; // samples; a wider halo reads more than any block it serves

// The halo's text, "[1, 1, 8]" (a recipe's list) or "1, 1, 8", as three sizes.
volume::Index3 parse_halo(const std::string& text) {
  static const std::regex form(R"(\s*\[?\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*\]?\s*)");
  std::smatch parts;
  volume::Index3 halo{0, 0, 0};
  bool ok = std::regex_match(text, parts, form);
  for (int a = 0; ok && a < 3; ++a) {
    const std::string digits = parts[a + 1];
    ok =
        std::from_chars(digits.data(), digits.data() + digits.size(), halo[a]).ec == std::errc() && halo[a] <= max_halo;
  }
  if (!ok)
    throw InvalidArgument("parameter 'halo' is '" + text + "': it must be three integers from 0 to " +
                              std::to_string(max_halo) + ", [inline, crossline, sample]",
                          {}, "the samples the function reads beyond the block on each side, e.g. halo: [1, 1, 8]");
  return halo;
}

class PythonStep final : public workflow::Plugin {
public:
  PythonStep() {
    params_ = {
        {.name = "function",
         .type = ParamType::text,
         .help = "the Python function, module:function, importable from 'path' or PYTHONPATH; it takes the block "
                 "plus its halo as a float32 array (inline, crossline, sample) and returns the block's attribute"},
        {.name = "halo",
         .type = ParamType::text,
         .default_value = "[0, 0, 0]",
         .help = "samples the function reads beyond the block on each side, [inline, crossline, sample]; mirrored "
                 "at the cube's faces",
         .unit = "samples",
         .list = true},
        {.name = "path",
         .type = ParamType::text,
         .default_value = ".",
         .help = "a directory searched for the module before PYTHONPATH, relative to the recipe's directory",
         .recipe_path = true},
    };
  }

  const std::string& name() const override { return name_; }
  workflow::StepKind kind() const override { return workflow::StepKind::attribute; }
  const std::string& summary() const override { return summary_; }
  const std::vector<workflow::ParamSpec>& params() const override { return params_; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }

  // Imports the function: a module that cannot be imported, or a name it lacks, is refused when the
  // recipe is read (and by every worker rebuilding the chain), not at the first block.
  void check(const workflow::ParamValues& values) const override {
    parse_halo(values.at("halo").text);
    import_function(values.at("function").text, values.at("path").text);
  }

  using Plugin::make_attribute;
  std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                 const workflow::ParamValues& values) const override {
    if (inputs.size() != 1)
      throw InvalidArgument("the python step takes one input, got " + std::to_string(inputs.size()));
    const std::string& function = values.at("function").text;
    auto callable = std::make_shared<const PyRef>(import_function(function, values.at("path").text));
    return std::make_shared<PythonAttribute>(std::move(inputs.front()), function, parse_halo(values.at("halo").text),
                                             std::move(callable));
  }

private:
  std::vector<workflow::ParamSpec> params_;
  std::string name_ = "python";
  std::string summary_ = "an attribute computed by a Python function on numpy blocks (function: module:function)";
  std::string origin_ = "built-in";
  std::string version_ = workflow::builtin_version;
};

} // namespace

void register_python_step(workflow::PluginRegistry& registry) {
  registry.add(std::make_shared<PythonStep>());
}

} // namespace geotandem::python_step
