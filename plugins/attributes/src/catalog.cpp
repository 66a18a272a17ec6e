#include "geotandem/attributes/catalog.hpp"

#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/attributes/normalise.hpp"
#include "geotandem/attributes/product.hpp"
#include "geotandem/attributes/rms.hpp"
#include "geotandem/attributes/semblance.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

// One row of the catalogue: the attribute's declaration, its check and its factory.
struct CatalogEntry {
  const AttributeSpec& (*spec)();
  void (*check)(const ParamValues& params);
  std::shared_ptr<Attribute> (*make)(const std::vector<VolumePtr>& inputs, const ParamValues& params);
};

// An attribute of one input built from its options (Name(input, NameOptions)).
template <class A, class Options> CatalogEntry unary() {
  return {&Options::spec, [](const ParamValues& p) { Options::from_params(p).validate(); },
          [](const std::vector<VolumePtr>& in, const ParamValues& p) -> std::shared_ptr<Attribute> {
            return std::make_shared<A>(in[0], Options::from_params(p));
          }};
}

// The whole catalogue, in the order builtin_attributes() lists it.
const std::vector<CatalogEntry>& catalog() {
  static const std::vector<CatalogEntry> entries = {
      unary<Envelope, EnvelopeOptions>(),
      unary<Rms, RmsOptions>(),
      unary<Semblance, SemblanceOptions>(),
      unary<Chaos, ChaosOptions>(),
      unary<Normalise, NormaliseOptions>(),
      {&ProductOptions::spec, [](const ParamValues& p) { (void)ProductOptions::from_params(p); },
       [](const std::vector<VolumePtr>& in, const ParamValues& p) -> std::shared_ptr<Attribute> {
         (void)ProductOptions::from_params(p); // it takes none: an unknown one is refused
         return std::make_shared<Product>(in[0], in[1]);
       }},
  };
  return entries;
}

const CatalogEntry& entry_of(std::string_view name) {
  for (const CatalogEntry& e : catalog())
    if (e.spec().name == name) return e;
  std::string known;
  for (const CatalogEntry& e : catalog())
    known += (known.empty() ? "" : ", ") + e.spec().name;
  throw InvalidArgument("unknown attribute '" + std::string(name) + "'", {}, "known attributes: " + known);
}

} // namespace

const std::vector<AttributeSpec>& builtin_attributes() {
  static const std::vector<AttributeSpec> specs = [] {
    std::vector<AttributeSpec> out;
    for (const CatalogEntry& e : catalog())
      out.push_back(e.spec());
    return out;
  }();
  return specs;
}

void check_params(std::string_view name, const ParamValues& params) {
  entry_of(name).check(params);
}

std::shared_ptr<Attribute> make_attribute(std::string_view name, std::vector<VolumePtr> inputs,
                                          const ParamValues& params) {
  const CatalogEntry& entry = entry_of(name);
  const AttributeSpec& spec = entry.spec();
  if (inputs.size() != static_cast<std::size_t>(spec.inputs))
    throw InvalidArgument("attribute '" + spec.name + "' takes " + std::to_string(spec.inputs) + " input" +
                          (spec.inputs == 1 ? "" : "s") + ", got " + std::to_string(inputs.size()));
  return entry.make(inputs, params);
}

} // namespace geotandem::attributes
