#include "geotandem/attributes/catalog.hpp"

#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/attributes/normalise.hpp"
#include "geotandem/attributes/product.hpp"
#include "geotandem/attributes/rms.hpp"
#include "geotandem/attributes/semblance.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {

const std::vector<AttributeSpec>& builtin_attributes() {
  static const std::vector<AttributeSpec> specs{EnvelopeOptions::spec(),  RmsOptions::spec(),
                                                SemblanceOptions::spec(), ChaosOptions::spec(),
                                                NormaliseOptions::spec(), ProductOptions::spec()};
  return specs;
}

namespace {

const AttributeSpec& spec_of(std::string_view name) {
  const AttributeSpec* spec = nullptr;
  for (const AttributeSpec& s : builtin_attributes())
    if (s.name == name) spec = &s;
  if (!spec) {
    std::string known;
    for (const AttributeSpec& s : builtin_attributes())
      known += (known.empty() ? "" : ", ") + s.name;
    throw InvalidArgument("unknown attribute '" + std::string(name) + "'", {}, "known attributes: " + known);
  }
  return *spec;
}

} // namespace

void check_params(std::string_view name, const ParamValues& params) {
  spec_of(name);
  if (name == "envelope") return EnvelopeOptions::from_params(params).validate();
  if (name == "rms") return RmsOptions::from_params(params).validate();
  if (name == "semblance") return SemblanceOptions::from_params(params).validate();
  if (name == "chaos") return ChaosOptions::from_params(params).validate();
  if (name == "normalise") return NormaliseOptions::from_params(params).validate();
  ProductOptions::from_params(params);
}

std::shared_ptr<Attribute> make_attribute(std::string_view name, std::vector<VolumePtr> inputs,
                                          const ParamValues& params) {
  const AttributeSpec* spec = &spec_of(name);
  if (inputs.size() != static_cast<std::size_t>(spec->inputs))
    throw InvalidArgument("attribute '" + spec->name + "' takes " + std::to_string(spec->inputs) + " input" +
                          (spec->inputs == 1 ? "" : "s") + ", got " + std::to_string(inputs.size()));

  if (name == "envelope") return std::make_shared<Envelope>(inputs[0], EnvelopeOptions::from_params(params));
  if (name == "rms") return std::make_shared<Rms>(inputs[0], RmsOptions::from_params(params));
  if (name == "semblance") return std::make_shared<Semblance>(inputs[0], SemblanceOptions::from_params(params));
  if (name == "chaos") return std::make_shared<Chaos>(inputs[0], ChaosOptions::from_params(params));
  if (name == "normalise") return std::make_shared<Normalise>(inputs[0], NormaliseOptions::from_params(params));
  ProductOptions::from_params(params);
  return std::make_shared<Product>(inputs[0], inputs[1]);
}

} // namespace geotandem::attributes
