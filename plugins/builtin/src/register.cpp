#include "geotandem/builtin/register.hpp"

#include <cmath>

#include "geotandem/attributes/catalog.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/workflow/builtin_steps.hpp"

namespace geotandem::builtin {
namespace {

workflow::ParamSpec convert(const attributes::ParamSpec& p) {
  workflow::ParamSpec s;
  s.name = p.name;
  switch (p.type) {
  case attributes::ParamType::integer: s.type = workflow::ParamType::integer; break;
  case attributes::ParamType::real: s.type = workflow::ParamType::real; break;
  case attributes::ParamType::choice: s.type = workflow::ParamType::choice; break;
  }
  s.default_value = attributes::to_string(p.default_value);
  s.help = p.help + (p.unit.empty() ? "" : " (" + p.unit + ")");
  s.unit = p.unit;
  s.odd = p.odd;
  if (std::isfinite(p.range.min)) {
    s.min_value = p.range.min;
    s.min_open = p.range.min_open;
  }
  if (std::isfinite(p.range.max)) {
    s.max_value = p.range.max;
    s.max_open = p.range.max_open;
  }
  s.choices = p.choices;
  return s;
}

class BuiltinAttribute final : public workflow::Plugin {
public:
  explicit BuiltinAttribute(const attributes::AttributeSpec& spec) : spec_(spec) {
    for (const auto& p : spec.params)
      params_.push_back(convert(p));
  }
  const std::string& name() const override { return spec_.name; }
  workflow::StepKind kind() const override { return workflow::StepKind::attribute; }
  const std::string& summary() const override { return spec_.summary; }
  const std::vector<workflow::ParamSpec>& params() const override { return params_; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }
  int input_count() const override { return spec_.inputs; }

  // Every single-parameter rule is in the converted spec; this runs the attribute's own
  // resolution too, so that any rule it adds later is still checked at validation.
  void check(const workflow::ParamValues& values) const override { attributes::resolve(spec_, given(values)); }

  using Plugin::make_attribute;
  std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                 const workflow::ParamValues& values) const override {
    return attributes::make_attribute(spec_.name, std::move(inputs), given(values));
  }

private:
  attributes::ParamValues given(const workflow::ParamValues& values) const {
    attributes::ParamValues out;
    for (const auto& p : spec_.params) {
      auto it = values.find(p.name);
      if (it == values.end()) continue;
      switch (p.type) {
      case attributes::ParamType::integer: out[p.name] = it->second.integer; break;
      case attributes::ParamType::real: out[p.name] = it->second.real; break;
      case attributes::ParamType::choice: out[p.name] = it->second.text; break;
      }
    }
    return out;
  }

  const attributes::AttributeSpec& spec_;
  std::vector<workflow::ParamSpec> params_;
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
