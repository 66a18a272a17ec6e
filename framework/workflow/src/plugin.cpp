#include "geotandem/workflow/plugin.hpp"

#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {

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

ExtractResult Plugin::extract(const volume::Volume&, store::ComponentStore&, const ParamValues&,
                              const ExecutionContext&, StepContext&) const {
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

} // namespace geotandem::workflow
