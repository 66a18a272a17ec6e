// Recipe parsing and validation: every error names file, line and column.

#include <gtest/gtest.h>

#include <filesystem>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/builtin_steps.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "test_paths.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

const char* good = R"(version: 1
input:
  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}
steps:
  - step: boxsum
    factor: 0.5
    as: smooth
  - step: extract
    iso: 0.3
    mode: tandem
  - step: remove_bubbles
    min_volume_fraction: 0.01
  - step: sort_by_azimuth
    bins: 12
output:
  directory: out
  exports:
    - {format: vtp, selection: kept}
execution:
  scheduler: slurm
  workers: 4
  resources: {memory: 4G, walltime: "01:30:00", queue: normal}
)";

class Recipes : public ::testing::Test {
protected:
  void SetUp() override {
    register_builtin_steps(registry);
    registry.load_library(test_paths::plugins() + "/boxsum/geotandem_boxsum.so");
  }

  // Parses `text`, expects an InvalidArgument and returns its message.
  std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
      parse_recipe(text, "dir/recipe.yaml", registry, overrides);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    ADD_FAILURE() << "recipe was accepted:\n" << text;
    return {};
  }

  std::string replaced(const std::string& from, const std::string& to) {
    std::string text = good;
    auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  }

  PluginRegistry registry;
};

} // namespace

TEST_F(Recipes, ValidRecipeWithDefaultsFilledIn) {
  Recipe r = parse_recipe(good, "dir/recipe.yaml", registry);
  EXPECT_TRUE(r.input.synthetic);
  EXPECT_EQ(r.input.shape[1], 48);
  ASSERT_EQ(r.steps.size(), 4u);
  EXPECT_EQ(r.steps[0].kind, StepKind::attribute);
  EXPECT_EQ(r.steps[0].inputs, std::vector<std::string>{"input"});
  EXPECT_DOUBLE_EQ(r.steps[0].params.at("factor").real, 0.5);
  EXPECT_EQ(r.steps[0].params.at("mode").text, "fast"); // default
  EXPECT_EQ(r.steps[1].kind, StepKind::extract);
  EXPECT_EQ(r.steps[1].inputs, std::vector<std::string>{"smooth"});
  EXPECT_DOUBLE_EQ(r.steps[1].params.at("max_error").real, 0.5);
  EXPECT_EQ(r.steps[1].params.at("mode").text, "tandem");
  EXPECT_EQ(r.steps[3].params.at("bins").integer, 12);
  EXPECT_EQ(r.execution.scheduler, "slurm");
  EXPECT_EQ(r.execution.workers, 4);
  EXPECT_EQ(r.execution.resources.memory_mb, 4096);
  EXPECT_EQ(r.execution.resources.walltime_s, 5400);
  EXPECT_EQ(r.output.exports.at(0).path, "bodies.vtp");
  EXPECT_EQ(r.base_dir, "dir");
  EXPECT_EQ(r.canonical["steps"][1]["params"]["iso"], "0.3");
}

TEST_F(Recipes, UnknownKeyNamesLineColumnAndNearestKey) {
  std::string e = error_of(replaced("    iso: 0.3", "    isovalue: 0.3"));
  // 'isovalue' replaces 'iso' at line 9, column 5; the step then lacks 'iso', reported at the key
  // that looks like it, with the suggestion.
  EXPECT_NE(e.find("dir/recipe.yaml:9:5: step 2 (extract) needs 'iso'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'iso'?"), std::string::npos) << e;
  std::string typo = error_of(replaced("    iso: 0.3", "    iso: 0.3\n    max_eror: 1"));
  EXPECT_NE(typo.find("dir/recipe.yaml:10:5: unknown key 'max_eror' in step 2 (extract)"), std::string::npos) << typo;
  EXPECT_NE(typo.find("did you mean 'max_error'?"), std::string::npos) << typo;
}

TEST_F(Recipes, UnknownTopLevelAndSectionKeys) {
  std::string e = error_of(std::string(good) + "outputs: {}\n");
  EXPECT_NE(e.find("recipe.yaml:23:1: unknown key 'outputs'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'output'?"), std::string::npos) << e;
  std::string s = error_of(replaced("  workers: 4", "  worker: 4"));
  EXPECT_NE(s.find("recipe.yaml:21:3: unknown key 'worker' in execution"), std::string::npos) << s;
}

// The input, output and execution sections are validated from their declarations as steps are:
// a misspelled key, at any depth, gets the nearest declared one with its line and column.
TEST_F(Recipes, MisspelledSectionKeysGetTheDeclaredNameWithLineAndColumn) {
  struct Case {
    std::string from, to, where, key, meant;
  };
  const std::vector<Case> cases = {
      {"  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}",
       "  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}\n  nann: fill", "recipe.yaml:4:3:", "nann", "nan"},
      {"seed: 3}", "sed: 3}", "recipe.yaml:3:51:", "sed", "seed"},
      {"  directory: out", "  directroy: out", "recipe.yaml:16:3:", "directroy", "directory"},
      {"  directory: out", "  directory: out\n  stor: s", "recipe.yaml:17:3:", "stor", "store"},
      {"  scheduler: slurm", "  schedulr: slurm", "recipe.yaml:20:3:", "schedulr", "scheduler"},
      {"queue: normal}", "queu: normal}", "recipe.yaml:22:49:", "queu", "queue"},
      {"  workers: 4", "  workers: 4\n  relay_memroy: 1G", "recipe.yaml:22:3:", "relay_memroy", "relay_memory"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(replaced(c.from, c.to));
    EXPECT_NE(e.find(c.where + " unknown key '" + c.key + "'"), std::string::npos) << e;
    EXPECT_NE(e.find("did you mean '" + c.meant + "'?"), std::string::npos) << e;
  }
  // A value checked by its declaration names the section, the key, and what it accepts.
  const std::string scheduler = error_of(replaced("  scheduler: slurm", "  scheduler: slurmm"));
  EXPECT_NE(scheduler.find("recipe.yaml:20:14: execution: parameter 'scheduler' is 'slurmm'"), std::string::npos)
      << scheduler;
  EXPECT_NE(scheduler.find("did you mean 'slurm'?"), std::string::npos) << scheduler;
  const std::string nan = error_of(replaced("seed: 3}", "seed: 3}\n  nan: drop"));
  EXPECT_NE(nan.find("recipe.yaml:4:8: input: parameter 'nan' is 'drop'"), std::string::npos) << nan;
}

TEST_F(Recipes, WrongTypesAndRanges) {
  std::string w = error_of(replaced("  workers: 4", "  workers: many"));
  EXPECT_NE(w.find("recipe.yaml:21:12: execution: parameter 'workers' is 'many', not an integer"), std::string::npos)
      << w;
  std::string r = error_of(replaced("    mode: tandem", "    mode: tandem\n    isotropy: 1.5"));
  EXPECT_NE(r.find("recipe.yaml:11:15:"), std::string::npos) << r;
  EXPECT_NE(r.find("out of range"), std::string::npos) << r;
  std::string c = error_of(replaced("    mode: tandem", "    mode: tandum"));
  EXPECT_NE(c.find("did you mean 'tandem'?"), std::string::npos) << c;
  std::string l = error_of(replaced("shape: [64, 48, 80]", "shape: [64, 48]"));
  EXPECT_NE(l.find("recipe.yaml:3:"), std::string::npos) << l;
  std::string m = error_of(replaced("memory: 4G", "memory: lots"));
  EXPECT_NE(m.find("execution.resources: parameter 'memory' is 'lots', not a size such as 2048M or 4G"),
            std::string::npos)
      << m;
  std::string z = error_of(replaced("memory: 4G", "memory: 0"));
  EXPECT_NE(z.find("parameter 'memory' is 0, out of range: it must be a size"), std::string::npos) << z;
  std::string t = error_of(replaced("\"01:30:00\"", "\"1:75\""));
  EXPECT_NE(t.find("parameter 'walltime' is '1:75', not a duration hh:mm:ss, hh:mm or minutes"), std::string::npos)
      << t;
  std::string a = error_of(replaced("queue: normal", "queue: normal, extra_args: [--exclusive, [x]]"));
  EXPECT_NE(a.find("entry 1 of 'extra_args'"), std::string::npos) << a;
}

TEST_F(Recipes, RelayMemoryIsASizeAndMayBeZero) {
  EXPECT_EQ(parse_recipe(good, "dir/recipe.yaml", registry).execution.relay_memory_mb, -1); // the runtime's
  EXPECT_EQ(parse_recipe(replaced("  workers: 4", "  workers: 4\n  relay_memory: 2G"), "dir/recipe.yaml", registry)
                .execution.relay_memory_mb,
            2048);
  EXPECT_EQ(parse_recipe(good, "dir/recipe.yaml", registry, {"execution.relay_memory=0"}).execution.relay_memory_mb, 0);
  std::string e = error_of(replaced("  workers: 4", "  workers: 4\n  relay_memory: -5M"));
  EXPECT_NE(e.find("recipe.yaml:22:17: execution: parameter 'relay_memory' is '-5M', not a size such as 2048M"),
            std::string::npos)
      << e;
  std::string g = error_of(replaced("  workers: 4", "  workers: 4\n  relay_memory: G"));
  EXPECT_NE(g.find("parameter 'relay_memory' is 'G'"), std::string::npos) << g;
  EXPECT_EQ(parse_recipe(replaced("  workers: 4", "  workers: 4\n  relay_memory: 1.5G"), "dir/recipe.yaml", registry)
                .execution.relay_memory_mb,
            1536);
}

TEST_F(Recipes, MissingParameterNamesItsHelp) {
  std::string e = error_of(replaced("    iso: 0.3\n", ""));
  EXPECT_NE(e.find("recipe.yaml:8:5: step 2 (extract) needs 'iso'"), std::string::npos) << e;
  EXPECT_NE(e.find("isovalue"), std::string::npos) << e;
}

TEST_F(Recipes, UnknownPluginSuggestsNearest) {
  std::string e = error_of(replaced("step: boxsum", "step: boxsun"));
  EXPECT_NE(e.find("recipe.yaml:5:11: unknown step or plugin 'boxsun'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'boxsum'?"), std::string::npos) << e;
  std::string b = error_of(replaced("step: remove_bubbles", "step: remove_bubble"));
  EXPECT_NE(b.find("did you mean 'remove_bubbles'?"), std::string::npos) << b;
}

TEST_F(Recipes, ChainOrderIsChecked) {
  std::string early = error_of(R"(input: {file: cube.nc}
steps:
  - step: remove_bubbles
  - step: extract
    iso: 1
)");
  EXPECT_NE(early.find("recipe.yaml:3:5: step 1 (remove_bubbles) works on components"), std::string::npos) << early;
  std::string none = error_of("input: {file: cube.nc}\nsteps:\n  - step: boxsum\n");
  EXPECT_NE(none.find("no extract step"), std::string::npos) << none;
  std::string dangling = error_of(replaced("    mode: tandem", "    mode: tandem\n    input: nowhere"));
  EXPECT_NE(dangling.find("reads 'nowhere'"), std::string::npos) << dangling;
}

TEST_F(Recipes, InputNeedsExactlyOneSource) {
  std::string both = error_of(replaced("  synthetic:", "  file: a.nc\n  synthetic:"));
  EXPECT_NE(both.find("exactly one of 'file' or 'synthetic'"), std::string::npos) << both;
}

TEST_F(Recipes, YamlSyntaxErrorHasLine) {
  std::string e = error_of("input: {file: cube.nc\nsteps: [\n");
  EXPECT_NE(e.find("dir/recipe.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("not valid YAML"), std::string::npos) << e;
}

TEST_F(Recipes, OverridesApplyByIndexOrNameAndAreValidated) {
  Recipe r =
      parse_recipe(good, "dir/recipe.yaml", registry,
                   {"execution.workers=8", "steps.extract.iso=0.7", "steps.1.factor=3", "input.synthetic.seed=9"});
  EXPECT_EQ(r.execution.workers, 8);
  EXPECT_DOUBLE_EQ(r.steps[1].params.at("iso").real, 0.7);
  EXPECT_DOUBLE_EQ(r.steps[0].params.at("factor").real, 3.0);
  EXPECT_EQ(r.input.seed, 9u);
  std::string bad = error_of(good, {"steps.extract.isotropy=7"});
  EXPECT_NE(bad.find("out of range"), std::string::npos) << bad;
  std::string typo = error_of(good, {"execution.wokers=2"});
  EXPECT_NE(typo.find("did you mean 'workers'?"), std::string::npos) << typo;
  EXPECT_THROW(parse_recipe(good, "r.yaml", registry, {"novalue"}), InvalidArgument);
  EXPECT_THROW(parse_recipe(good, "r.yaml", registry, {"steps.nosuchstep.iso=1"}), InvalidArgument);
}

TEST_F(Recipes, AnErrorInAnOverriddenValueNamesTheSetNotALineOfTheFile) {
  // The value of a --set is parsed on its own: its positions are within the value. They used to be
  // reported as lines and columns of the recipe ("dir/recipe.yaml:1:5").
  std::string shape = error_of(good, {"execution.workers=3", "input.synthetic.shape=[64, 2, 80]"});
  EXPECT_EQ(shape.rfind("--set input.synthetic.shape=[64, 2, 80]: input.synthetic: parameter 'shape[1]' is 2, out of "
                        "range: it must be an integer in [40, 100000]",
                        0),
            0u)
      << shape;
  std::string range = error_of(good, {"steps.extract.isotropy=7"});
  EXPECT_EQ(range.rfind("--set steps.extract.isotropy=7: ", 0), 0u) << range;
  std::string key = error_of(good, {"execution={workers: 2, wokers: 3}"});
  EXPECT_EQ(key.rfind("--set execution={workers: 2, wokers: 3}: unknown key 'wokers'", 0), 0u) << key;
  std::string added = error_of(good, {"execution.wokers=3"}); // the key itself comes from the --set
  EXPECT_EQ(added.rfind("--set execution.wokers=3: unknown key 'wokers'", 0), 0u) << added;
  // The second override of a key replaces the first: the error is the second's.
  std::string twice = error_of(good, {"execution.workers=0", "execution.workers=-1"});
  EXPECT_EQ(twice.rfind("--set execution.workers=-1: ", 0), 0u) << twice;
  // An error in the file keeps its line and column with overrides elsewhere.
  std::string in_file = error_of(replaced("workers: 4", "workers: 0"), {"steps.extract.iso=0.7"});
  EXPECT_EQ(in_file.rfind("dir/recipe.yaml:21:12: execution: parameter 'workers' is 0", 0), 0u) << in_file;
  // A path through a value is refused as such (it used to fail inside YAML as "not valid YAML").
  std::string through = error_of(good, {"input.synthetic.kind.x=1"});
  EXPECT_EQ(through.rfind("--set input.synthetic.kind.x=1: 'kind' holds a value ('seismic'), not keys", 0), 0u)
      << through;
  // A step given whole by a --set replaces the step (it used to turn the list into a mapping), and
  // has no line in the file to report later.
  Recipe r = parse_recipe(good, "dir/recipe.yaml", registry, {"steps.1={step: boxsum, factor: 2}"});
  ASSERT_EQ(r.steps.size(), 4u);
  EXPECT_EQ(r.steps[0].name, "boxsum");
  EXPECT_DOUBLE_EQ(r.steps[0].params.at("factor").real, 2.0);
  EXPECT_EQ(r.steps[0].where.line, 0);
  EXPECT_GT(r.steps[1].where.line, 0);
}

TEST_F(Recipes, SegyHeaderBytesComeFromTheInputSection) {
  const std::string file_input = replaced("  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}",
                                          "  file: f3.sgy\n  segy: {inline_byte: 9, crossline_byte: 21}");
  Recipe r = parse_recipe(file_input, "dir/recipe.yaml", registry);
  EXPECT_EQ(r.input.segy.inline_byte, 9);
  EXPECT_EQ(r.input.segy.crossline_byte, 21);
  EXPECT_EQ(r.canonical["input"]["segy"]["crossline_byte"], 21);
  Recipe standard =
      parse_recipe(replaced("  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}", "  file: a.sgy"),
                   "dir/recipe.yaml", registry, {"input.segy.inline_byte=5"});
  EXPECT_EQ(standard.input.segy.inline_byte, 5);
  EXPECT_EQ(standard.input.segy.crossline_byte, 193);

  std::string typo = error_of(file_input, {"input.segy.inline_bite=9"});
  EXPECT_NE(typo.find("did you mean 'inline_byte'?"), std::string::npos) << typo;
  std::string range = error_of(file_input, {"input.segy.crossline_byte=400"});
  EXPECT_NE(range.find("crossline_byte"), std::string::npos) << range;
}

// input.no_data: the null of a file that cannot declare one, a float sample's value, for files only.
TEST_F(Recipes, NoDataValueComesFromTheInputSection) {
  const std::string file_input =
      replaced("  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}", "  file: f3.sgy\n  no_data: -999.25");
  Recipe r = parse_recipe(file_input, "dir/recipe.yaml", registry);
  ASSERT_TRUE(r.input.no_data.has_value());
  EXPECT_EQ(*r.input.no_data, -999.25);
  EXPECT_EQ(r.canonical["input"]["no_data"], -999.25);
  Recipe none = parse_recipe(replaced("  synthetic: {kind: seismic, shape: [64, 48, 80], seed: 3}", "  file: a.sgy"),
                             "dir/recipe.yaml", registry);
  EXPECT_FALSE(none.input.no_data.has_value());
  EXPECT_FALSE(none.canonical["input"].contains("no_data")) << "a recipe without it keeps its old identity";

  std::string range = error_of(file_input, {"input.no_data=1e39"});
  EXPECT_NE(range.find("no_data"), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;
  std::string text = error_of(file_input, {"input.no_data=dead"});
  EXPECT_NE(text.find("parameter 'no_data' is 'dead', not a real"), std::string::npos) << text;
  std::string synthetic = error_of(replaced("seed: 3}", "seed: 3}\n  no_data: 0"));
  EXPECT_NE(synthetic.find("dir/recipe.yaml:4:"), std::string::npos) << synthetic;
  EXPECT_NE(synthetic.find("file input"), std::string::npos) << synthetic;
}

TEST_F(Recipes, AttributeFileOfUnknownFormatIsRefusedAtValidation) {
  // Caught before any work, not after the extraction when the cube is written.
  std::string e = error_of(replaced("  directory: out\n", "  directory: out\n  attribute: smooth.xyz\n"));
  EXPECT_NE(e.find("recipe.yaml:17:14: output.attribute: cannot tell the output format from the extension '.xyz'"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find(".nc (netCDF-4)"), std::string::npos) << e;
  parse_recipe(replaced("  directory: out\n", "  directory: out\n  attribute: smooth.nc\n"), "dir/recipe.yaml",
               registry);
}

// output.labels (issue 54): the label cube is written in the input's format family, and a recipe
// naming another is refused at validation, at the line of `labels:`, naming the extension to use; a
// synthetic input takes any writable format. side: below is a choice of the extract step.
TEST_F(Recipes, LabelsFollowTheInputsFormatFamily) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "recipe-labels";
  std::filesystem::create_directories(dir);
  volume::Geometry g;
  g.shape = {4, 4, 4};
  volume::MemoryVolume cube(g, std::vector<float>(64, 0.0f));
  volume::WriteOptions overwrite;
  overwrite.overwrite = true;
  volume::write_volume(cube, (dir / "cube.segy").string(), overwrite);
  const auto recipe = [](const std::string& labels) {
    return "input: {file: cube.segy}\nsteps:\n  - {step: extract, iso: 0.5, side: below}\noutput:\n  labels: " +
           labels + "\n";
  };
  const std::string path = (dir / "recipe.yaml").string();
  try {
    parse_recipe(recipe("labels.nc"), path, registry);
    ADD_FAILURE() << "a netCDF label cube of a SEG-Y input was accepted";
  } catch (const InvalidArgument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("output.labels"), std::string::npos) << m;
    EXPECT_NE(m.find("SEG-Y"), std::string::npos) << m;
    EXPECT_NE(m.find("labels.segy"), std::string::npos) << m;
    EXPECT_NE(m.find(":5:"), std::string::npos) << m;
  }
  const Recipe r = parse_recipe(recipe("labels.sgy"), path, registry);
  EXPECT_EQ(r.output.labels_file, "labels.sgy");
  EXPECT_EQ(r.steps.at(0).params.at("side").text, "below");
  EXPECT_NE(error_of(replaced("    mode: tandem", "    mode: tandem\n    side: low")).find("side"), std::string::npos);
  EXPECT_EQ(
      parse_recipe(replaced("  directory: out", "  directory: out\n  labels: ids.tif"), "dir/recipe.yaml", registry)
          .output.labels_file,
      "ids.tif");
  EXPECT_NE(error_of(replaced("  directory: out", "  directory: out\n  labels: ids.xyz")).find("output.labels"),
            std::string::npos);
}
