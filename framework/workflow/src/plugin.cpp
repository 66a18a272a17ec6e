#include "geotandem/workflow/plugin.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/report.hpp"
#include "geotandem/workflow/suggest.hpp"

namespace geotandem::workflow {

const char* to_string(ParamType type) {
  switch (type) {
  case ParamType::integer: return "integer";
  case ParamType::real: return "number";
  case ParamType::boolean: return "boolean";
  case ParamType::text: return "text";
  case ParamType::choice: return "choice";
  }
  return "?";
}

const char* to_string(StepKind kind) {
  switch (kind) {
  case StepKind::attribute: return "attribute";
  case StepKind::extract: return "extraction";
  case StepKind::component: return "component step";
  case StepKind::export_step: return "export";
  case StepKind::report: return "report";
  }
  return "?";
}

void Plugin::refuse(const char* what) const {
  throw InvalidArgument("step '" + name() + "' is " + (kind() == StepKind::attribute ? "an " : "a ") +
                            to_string(kind()) + " and cannot " + what,
                        {origin()}, "use it where its kind belongs in the chain (see 'geotandem plugins')");
}

std::shared_ptr<volume::Volume> Plugin::make_attribute(std::vector<std::shared_ptr<const volume::Volume>>,
                                                       const ParamValues&) const {
  refuse("compute an attribute");
}

ExtractResult Plugin::extract(const volume::Volume&, store::ComponentStore&, const ParamValues&, const nlohmann::json&,
                              StepContext&) const {
  refuse("extract an isosurface");
}

ComponentOutcome Plugin::select(store::ComponentStore&, const ParamValues&, const std::string&, StepContext&) const {
  refuse("select components");
}

ExportOutcome Plugin::export_components(const store::ComponentStore&, const ParamValues&, const std::string&,
                                        const std::filesystem::path&, StepContext&) const {
  refuse("export components");
}

std::string Plugin::write_report(const ReportData&, const ParamValues&, const std::filesystem::path&) const {
  refuse("write a report");
}

namespace {

std::string range_text(const ParamSpec& spec) {
  std::ostringstream out;
  if (spec.min_value && spec.max_value && !spec.min_open && !spec.max_open) {
    out << "between " << *spec.min_value << " and " << *spec.max_value;
    return out.str();
  }
  if (spec.min_value) out << (spec.min_open ? "above " : "at least ") << *spec.min_value;
  if (spec.min_value && spec.max_value) out << " and ";
  if (spec.max_value) out << (spec.max_open ? "below " : "at most ") << *spec.max_value;
  return out.str();
}

void check_range(const ParamSpec& spec, double value, const std::string& text) {
  bool low = spec.min_value && (spec.min_open ? value <= *spec.min_value : value < *spec.min_value);
  bool high = spec.max_value && (spec.max_open ? value >= *spec.max_value : value > *spec.max_value);
  if (low || high)
    throw InvalidArgument("parameter '" + spec.name + "' is " + text + ", out of range", {},
                          "use a value " + range_text(spec));
}

} // namespace

ParamValue parse_param(const ParamSpec& spec, const std::string& text) {
  ParamValue v;
  v.type = spec.type;
  v.text = text;
  auto bad = [&](const char* expected) {
    return InvalidArgument("parameter '" + spec.name + "' is '" + text + "', not " + expected, {},
                           spec.help.empty() ? std::string() : spec.name + ": " + spec.help);
  };
  switch (spec.type) {
  case ParamType::integer: {
    char* end = nullptr;
    errno = 0;
    long long n = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno) throw bad("an integer");
    v.integer = n;
    v.real = static_cast<double>(n);
    check_range(spec, v.real, text);
    if (spec.odd && n % 2 == 0)
      throw InvalidArgument("parameter '" + spec.name + "' is " + text + ", not odd", {},
                            "a centred window has an odd length: use " + std::to_string(n - 1) + " or " +
                                std::to_string(n + 1));
    break;
  }
  case ParamType::real: {
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno || !std::isfinite(x)) throw bad("a number");
    v.real = x;
    check_range(spec, x, text);
    break;
  }
  case ParamType::boolean:
    if (text == "true" || text == "yes" || text == "on")
      v.boolean = true;
    else if (text == "false" || text == "no" || text == "off")
      v.boolean = false;
    else
      throw bad("true or false");
    break;
  case ParamType::text: break;
  case ParamType::choice: {
    bool known = false;
    for (const auto& c : spec.choices)
      known = known || c == text;
    if (!known)
      throw InvalidArgument("parameter '" + spec.name + "' is '" + text + "', not a known choice", {},
                            suggestion_hint(text, spec.choices));
    break;
  }
  }
  return v;
}

ParamValues default_values(const std::vector<ParamSpec>& specs) {
  ParamValues values;
  for (const auto& spec : specs) {
    if (!spec.default_value)
      throw InvalidArgument("parameter '" + spec.name + "' has no default", {}, spec.name + ": " + spec.help);
    values[spec.name] = parse_param(spec, *spec.default_value);
  }
  return values;
}

} // namespace geotandem::workflow
