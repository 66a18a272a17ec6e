// geotandem run-workflow RECIPE: what a geophysicist runs.

#include <iostream>

#include "command.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/runner.hpp"
#include "plugins_setup.hpp"

namespace geotandem::app {

void add_workflow_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string recipe;
    std::vector<std::string> sets;
    bool dry_run = false;
    bool fresh = false;
    std::string scheduler;
    std::string bind;
    std::string crs;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "run-workflow",
      "Run a recipe: compute the attribute, extract its isosurface into a component store, run the component "
      "steps (remove bubbles, sort by azimuth, plugins), export and write an HTML report. A rerun reuses the "
      "finished extraction.");
  cmd->add_option("recipe", args->recipe, "the recipe (YAML); see docs/recipe-schema.md and workflows/")->required();
  cmd->add_option("--set", args->sets, "override a recipe value, e.g. --set steps.extract.iso=0.4 (repeatable)");
  cmd->add_flag("--dry-run", args->dry_run,
                "validate the recipe and build the whole chain (plugins, parameters, input), then stop: "
                "nothing is computed and nothing is written");
  cmd->add_flag("--fresh", args->fresh, "replace a store left in the output directory by other parameters");
  cmd->add_option("--scheduler", args->scheduler,
                  "where the extraction's workers run: local, slurm or lsf (overrides execution.scheduler; "
                  "execution.workers and execution.resources say how many and with what)");
  cmd->add_option("--bind", args->bind,
                  "where the manager listens for its workers: loopback (the default), an interface (ib0) or an "
                  "address (10.0.0.5[:PORT]); anything but loopback turns CurveZMQ on (overrides execution.bind)");
  add_crs_option(*cmd, args->crs);
  cmd->callback([args, &context, &run] {
    run = [args, &context] {
      crs_option(args->crs); // a wrong code is named as --crs's, before the recipe is read
      auto registry = make_plugin_registry(context.log);
      auto sets = args->sets;
      if (!args->crs.empty()) {
        // A YAML single-quoted scalar: a WKT's brackets, commas and double quotes stay text.
        std::string quoted = "'";
        for (char c : args->crs)
          quoted += c == '\'' ? std::string("''") : std::string(1, c);
        sets.push_back("input.crs=" + quoted + "'");
      }
      if (!args->scheduler.empty()) sets.push_back("execution.scheduler=" + args->scheduler);
      if (!args->bind.empty()) sets.push_back("execution.bind=" + args->bind);
      auto recipe = workflow::load_recipe(args->recipe, registry, sets);
      workflow::WorkflowSettings settings;
      settings.dry_run = args->dry_run;
      settings.fresh = args->fresh;
      settings.progress = [&context] { return context.progress(); };
      settings.worker_command = worker_command(context);
      auto outcome = workflow::run_workflow(recipe, registry, settings, context.log, context.cancel);
      // Interrupted after the last step polled the token: still an interrupted run (exit 130), never 0.
      context.cancel.throw_if_cancelled();
      if (args->dry_run) {
        std::cout << args->recipe << ": valid; nothing computed (dry run)\n";
        return 0;
      }
      std::cout << "components: " << outcome.components << " extracted"
                << (outcome.extraction_reused ? " (reused)" : "") << ", " << outcome.kept << " kept\n"
                << "store:      " << outcome.store_dir << "\n"
                << "report:     " << outcome.report << "\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
