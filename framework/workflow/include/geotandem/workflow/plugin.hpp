#pragma once
// Steps as the host sees them. Every step of a recipe, built-in or loaded through the C ABI
// (plugin_abi.h), is a Plugin in one PluginRegistry, with one lifecycle:
//   1. declare: a name, a kind, and its parameters (name, type, default, range, help);
//   2. validate: the whole recipe is checked against those declarations (parse_param) and each
//      step's check() before any work starts, so `geotandem validate` sees what a run would refuse;
//   3. run: the runner calls the entry point of the step's kind, never a step by name.
// The runner walks a chain of attribute steps, one extraction, component steps, exports and the
// report; a step implements the entry point of its kind and inherits a refusal for the others.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/params.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/plugin_abi.h"

namespace geotandem::store {
class ComponentStore;
}

namespace geotandem::workflow {

struct ExtractResult;
struct ExecutionContext;
struct ReportData;

// The one parameter model (geotandem/core/params.hpp), shared with the built-in attributes; the C
// ABI's gt_param_spec is its C form (mapped in abi_plugin.cpp).
using geotandem::default_values;
using geotandem::ParamSpec;
using geotandem::ParamType;
using geotandem::ParamValue;
using geotandem::ParamValues;
using geotandem::parse_param;
using geotandem::to_string;

// The kinds of steps, in the order a chain runs them: volume steps (attributes, including
// combinators such as a product), one extraction, component steps, exports, the report.
enum class StepKind { attribute, extract, component, export_step, report };
using PluginKind = StepKind;
// "attribute", "extraction", "component step", "export", "report".
const char* to_string(StepKind kind);

// What a running step may use.
struct StepContext {
  Logger& log;
  Progress& progress;
  const CancelToken& cancel;
};

// What a component step did: it wrote `selection` into the store.
struct ComponentOutcome {
  std::uint64_t before = 0;
  std::uint64_t after = 0;
  std::string selection;
  std::string note; // one line for the report
  // Figures for the report's plots, by name: "volume_threshold" (the bubble threshold line of the
  // volume histogram), "azimuth_bins" (the rose diagram's bins).
  std::map<std::string, double> figures;
};

struct ExportOutcome {
  std::uint64_t rows = 0;       // components asked for
  std::uint64_t components = 0; // written
  std::string path;             // relative to the output directory; empty when nothing was written
};

class Plugin {
public:
  virtual ~Plugin() = default;
  virtual const std::string& name() const = 0;
  virtual StepKind kind() const = 0;
  virtual const std::string& summary() const = 0;
  virtual const std::vector<ParamSpec>& params() const = 0;
  // Where it comes from: "built-in" or the shared library's path; and its own version.
  virtual const std::string& origin() const = 0;
  virtual const std::string& version() const = 0;

  // How many input volumes an attribute combines (1 for most; 2 for a product); 0 for steps that
  // do not read volumes.
  virtual int input_count() const { return kind() == StepKind::attribute || kind() == StepKind::extract ? 1 : 0; }

  // Validation beyond each parameter's own spec (combinations, odd window lengths, excluded
  // values): throws InvalidArgument naming the parameter. `values` holds every parameter.
  virtual void check(const ParamValues& values) const { (void)values; }

  // Attribute steps: the attribute of `inputs` (input_count() of them, same shape) as a lazy
  // volume with their geometry. Throws InvalidArgument for a wrong number of inputs.
  virtual std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                         const ParamValues& values) const;
  std::shared_ptr<volume::Volume> make_attribute(std::shared_ptr<const volume::Volume> input,
                                                 const ParamValues& values) const {
    return make_attribute(std::vector<std::shared_ptr<const volume::Volume>>{std::move(input)}, values);
  }

  // The extraction step: the isosurface of `input` into `store`; `execution` says where it runs
  // (in this process or with workers) and what the run records besides the parameters.
  virtual ExtractResult extract(const volume::Volume& input, store::ComponentStore& store, const ParamValues& values,
                                const ExecutionContext& execution, StepContext& context) const;

  // Component steps: read the components of selection `from` (empty: every component) and write a
  // named selection.
  virtual ComponentOutcome select(store::ComponentStore& store, const ParamValues& values, const std::string& from,
                                  StepContext& context) const;

  // Export steps: write the components of their selection (or of `current`, the newest one) under
  // `out_dir`.
  virtual ExportOutcome export_components(const store::ComponentStore& store, const ParamValues& values,
                                          const std::string& current, const std::filesystem::path& out_dir,
                                          StepContext& context) const;

  // The report step: writes the report of `data` under `out_dir`; returns the file's path.
  virtual std::string write_report(const ReportData& data, const ParamValues& values,
                                   const std::filesystem::path& out_dir) const;

private:
  [[noreturn]] void refuse(const char* what) const;
};

// Wraps a descriptor returned by a plugin's entry point (or a built-in's static descriptor).
// `origin` names the file for messages. Validates the descriptor (size, version, kind, names,
// parameter specs) and throws FormatError naming `origin` when it is wrong. A descriptor of an
// older minor version (a smaller struct_size) is read up to the fields it has.
std::shared_ptr<Plugin> plugin_from_descriptor(const gt_plugin_descriptor* descriptor, const std::string& origin);

} // namespace geotandem::workflow
