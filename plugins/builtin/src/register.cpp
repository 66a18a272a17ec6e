#include "geotandem/builtin/register.hpp"

#include "geotandem/attributes/catalog.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/workflow/builtin_steps.hpp"

namespace geotandem::builtin {
namespace {

class BuiltinAttribute final : public workflow::Plugin {
public:
  // The attribute's own declarations are the registry's: one parameter model, no conversion.
  explicit BuiltinAttribute(const attributes::AttributeSpec& spec) : spec_(spec) {}
  const std::string& name() const override { return spec_.name; }
  workflow::StepKind kind() const override { return workflow::StepKind::attribute; }
  const std::string& summary() const override { return spec_.summary; }
  const std::vector<workflow::ParamSpec>& params() const override { return spec_.params; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }
  int input_count() const override { return spec_.inputs; }

  // The recipe's values were checked against these very declarations; building the options checks
  // whatever an attribute adds beyond single parameters, so validation refuses what a run would.
  void check(const workflow::ParamValues& values) const override { attributes::check_params(spec_.name, values); }

  using Plugin::make_attribute;
  std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                 const workflow::ParamValues& values) const override {
    return attributes::make_attribute(spec_.name, std::move(inputs), values);
  }

private:
  const attributes::AttributeSpec& spec_;
  std::string origin_ = "built-in";
  std::string version_ = workflow::builtin_version;
};

} // namespace

void register_attributes(workflow::PluginRegistry& registry) {
  for (const auto& spec : attributes::builtin_attributes())
    registry.add(std::make_shared<BuiltinAttribute>(spec));
}

void register_builtins(workflow::PluginRegistry& registry) {
  register_attributes(registry);
  workflow::register_builtin_steps(registry);
}

} // namespace geotandem::builtin
