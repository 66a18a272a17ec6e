// geotandem plugins [NAME] and geotandem validate RECIPE: what a recipe may use, and whether a
// recipe is right, without running anything.

#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>

#include "command.hpp"
#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/recipe_schema.hpp"
#include "geotandem/workflow/registry.hpp"
#include "plugins_setup.hpp"

namespace geotandem::app {
namespace {

// `absent`: what a key without a default means when it is left out (a recipe section's optional
// keys); any other key without a default is required.
void print_params(const std::vector<workflow::ParamSpec>& specs,
                  const std::map<std::string, std::string>& absent = {}) {
  for (const auto& p : specs) {
    const auto left_out = absent.find(p.name);
    std::cout << "    " << std::left << std::setw(24) << p.name << std::setw(9) << workflow::to_string(p.type)
              << (p.default_value            ? "default " + *p.default_value
                  : left_out != absent.end() ? "without it: " + left_out->second
                                             : std::string("required"))
              << "; " << p.valid_values() << "\n      " << p.help << (p.unit.empty() ? "" : " (" + p.unit + ")")
              << "\n";
  }
}

// The recipe's sections (input, input.segy, ..., execution.resources): their keys by name.
void list_sections() {
  std::cout << "recipe sections:\n";
  for (const auto& section : workflow::recipe_sections()) {
    std::cout << "  " << std::left << std::setw(22) << section.path << "keys:";
    for (const auto& key : section.keys)
      std::cout << ' ' << key.name;
    std::cout << "\n";
  }
}

} // namespace

void add_plugins_command(CLI::App& app, Context& context, Runner& run) {
  auto name = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("plugins", "List every step a recipe can use (attributes, the extraction, component "
                                            "steps, exports, the report; built-in or loaded) with its kind and "
                                            "parameters, and the recipe's sections with their keys; or describe "
                                            "one.");
  cmd->add_option("name", *name,
                  "a step, or a recipe section (input, input.segy, execution.resources, ...), to "
                  "describe");
  auto schema_doc = std::make_shared<std::string>();
  cmd->add_option("--schema-doc", *schema_doc,
                  "print FILE (docs/recipe-schema.md) with its generated tables made anew from the declarations of "
                  "the recipe's sections and the built-in steps (the lines between '<!-- generated: WHAT -->' and "
                  "'<!-- end generated -->')")
      ->type_name("FILE");
  cmd->callback([name, schema_doc, &context, &run] {
    run = [name, schema_doc, &context] {
      if (!schema_doc->empty()) {
        // The built-in steps only: a plugin on this machine's search path is not part of the docs.
        workflow::PluginRegistry builtins;
        builtin::register_builtins(builtins);
        std::ifstream in(*schema_doc);
        if (!in) throw IoError("cannot read the schema document", {*schema_doc});
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::cout << workflow::regenerate_schema_doc(text, builtins);
        return 0;
      }
      auto registry = make_plugin_registry(context.log);
      if (!name->empty()) {
        for (const auto& section : workflow::recipe_sections())
          if (section.path == *name) {
            std::cout << "recipe section " << section.path << "\n  keys:\n";
            print_params(section.keys, section.absent);
            return 0;
          }
        const auto& p = registry.get(*name);
        std::cout << p.name() << " (" << workflow::to_string(p.kind()) << ", " << p.origin() << ", version "
                  << p.version() << ")\n  " << p.summary() << "\n  parameters:\n";
        print_params(p.params());
        return 0;
      }
      const std::pair<workflow::StepKind, const char*> kinds[] = {{workflow::StepKind::attribute, "attributes"},
                                                                  {workflow::StepKind::extract, "extraction"},
                                                                  {workflow::StepKind::component, "component steps"},
                                                                  {workflow::StepKind::export_step, "exports"},
                                                                  {workflow::StepKind::report, "report"}};
      for (const auto& [kind, heading] : kinds) {
        std::cout << heading << ":\n";
        for (const auto* p : registry.list()) {
          if (p->kind() != kind) continue;
          std::cout << "  " << std::left << std::setw(16) << p->name() << p->summary()
                    << (p->origin() == "built-in" ? "" : "  [" + p->origin() + "]") << "\n      parameters:";
          for (const auto& spec : p->params())
            std::cout << ' ' << spec.name;
          std::cout << (p->params().empty() ? " none\n" : "\n");
        }
      }
      list_sections();
      std::cout << "'geotandem plugins NAME' describes one step's parameters or one recipe section's keys\n";
      std::cout << "plugin search path: " << workflow::PluginRegistry::default_search_path() << "\n";
      return 0;
    };
  });
}

void add_validate_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string recipe;
    std::vector<std::string> sets;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("validate", "Check a recipe completely (keys, types, ranges, plugins, step order) "
                                             "without running it.");
  cmd->add_option("recipe", args->recipe, "the recipe (YAML)")->required();
  cmd->add_option("--set", args->sets, "override a recipe value, e.g. --set steps.extract.iso=0.4");
  cmd->callback([args, &context, &run] {
    run = [args, &context] {
      auto registry = make_plugin_registry(context.log);
      auto recipe = workflow::load_recipe(args->recipe, registry, args->sets);
      std::cout << args->recipe << ": valid, " << recipe.steps.size() << " steps:";
      for (const auto& s : recipe.steps)
        std::cout << ' ' << s.name;
      // Without `workers`, a local run takes one worker per core, at most one per block
      // (default_worker_count): the cube is not opened here to count them.
      const workflow::ExecutionSpec& ex = recipe.execution;
      std::cout << "; scheduler " << ex.scheduler << " with ";
      if (ex.workers_given || ex.scheduler != "local")
        std::cout << ex.workers << " worker(s)\n";
      else
        std::cout << "one worker per core, at most one per block\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
