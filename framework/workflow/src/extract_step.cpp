#include "geotandem/workflow/extract_step.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/fingerprint.hpp"
#include "geotandem/workflow/chain.hpp"
#include "param_builder.hpp"

namespace geotandem::workflow {

ExtractMode parse_extract_mode(const std::string& text) {
  if (text == "tandem-dump") return ExtractMode::tandem_dump;
  if (text == "tandem") return ExtractMode::tandem;
  if (text == "brute") return ExtractMode::brute;
  throw InvalidArgument("unknown extraction mode '" + text + "'", {}, "use tandem-dump, tandem or brute");
}

const char* to_string(ExtractMode mode) {
  switch (mode) {
  case ExtractMode::tandem_dump: return "tandem-dump";
  case ExtractMode::tandem: return "tandem";
  case ExtractMode::brute: return "brute";
  }
  return "?";
}

int parse_axis(const std::string& text) {
  if (text == "i" || text == "0") return 0;
  if (text == "j" || text == "1") return 1;
  if (text == "k" || text == "2") return 2;
  throw InvalidArgument("unknown axis '" + text + "'", {}, "use i (inline), j (crossline) or k (sample)");
}

bool parse_side(const std::string& text) {
  if (text == "above") return false;
  if (text == "below") return true;
  throw InvalidArgument("unknown side '" + text + "'", {}, "use above (value >= iso) or below (value <= iso)");
}

namespace {

// The isovalue is compared with float samples: a value beyond the float range is refused, not inf.
ParamSpec single_precision(ParamSpec spec) {
  spec.single_precision = true;
  return spec;
}

std::vector<ParamSpec> make_extract_params() {
  const ExtractSettings d;
  return {
      single_precision(
          detail::param_spec("iso", ParamType::real, std::nullopt,
                             "isovalue: samples >= iso (side above) or <= iso (side below) are inside a body")),
      detail::param_spec("side", ParamType::choice, side_text(d.below),
                         "which side of iso is inside a body: above (value >= iso) or below (value <= iso: low "
                         "coherence, low impedance)",
                         {}, {}, {"above", "below"}),
      detail::param_spec("max_error", ParamType::real, number_text(d.max_error),
                         "E0, in voxels: the simplified surface stays within E0 of the full-resolution one", 1e-6,
                         100.0),
      detail::param_spec("isotropy", ParamType::real, number_text(d.isotropy),
                         "alpha, weight of triangle shape against surface fidelity", 0.0, 1.0),
      detail::param_spec("axis", ParamType::choice, std::string(1, "ijk"[d.axis]),
                         "extraction axis: i (inline), j (crossline) or k (sample)", {}, {}, {"i", "j", "k"}),
      detail::param_spec("block_size", ParamType::integer, std::to_string(d.block_size),
                         "leaf block edge in cells for the block tree: 0 (the whole cube as one block) or at least " +
                             std::to_string(min_block_size),
                         0.0, 4096.0),
      detail::param_spec("mode", ParamType::choice, to_string(d.mode),
                         "tandem-dump (default), tandem (no early dumping), brute (extract, then simplify)", {}, {},
                         {"tandem-dump", "tandem", "brute"}),
      detail::param_spec("extended_time_lag", ParamType::boolean, d.extended_time_lag ? "true" : "false",
                         "delay collapses near open block faces (the seed's section 3.2)"),
  };
}

} // namespace

const std::vector<ParamSpec>& extract_params() {
  static const std::vector<ParamSpec> specs = make_extract_params();
  return specs;
}

void check_extract_params(const ParamValues& values) {
  std::int64_t block = values.at("block_size").integer;
  if (block != 0 && block < min_block_size)
    throw InvalidArgument("parameter 'block_size' is " + std::to_string(block) + ", below the smallest block of " +
                              std::to_string(min_block_size) + " cells",
                          {},
                          "use 0 (one block) or at least " + std::to_string(min_block_size) +
                              "; blocks of 64 to 256 cells are typical");
}

ExtractSettings extract_settings(const ParamValues& values) {
  check_extract_params(values);
  ExtractSettings e;
  e.iso = static_cast<float>(values.at("iso").real);
  // Absent from values made before the parameter existed (a chain described by an older run).
  if (auto side = values.find("side"); side != values.end()) e.below = parse_side(side->second.text);
  e.max_error = values.at("max_error").real;
  e.isotropy = values.at("isotropy").real;
  e.axis = parse_axis(values.at("axis").text);
  e.block_size = values.at("block_size").integer;
  e.mode = parse_extract_mode(values.at("mode").text);
  e.extended_time_lag = values.at("extended_time_lag").boolean;
  return e;
}

std::int64_t peak_rss_kb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6));
  return 0;
}

nlohmann::json extract_run_parameters(const volume::Volume& volume, const ExtractSettings& settings) {
  nlohmann::json parameters = settings.parameters;
  parameters["iso"] = settings.iso;
  parameters["side"] = side_text(settings.below);
  parameters["max_error"] = settings.max_error;
  parameters["isotropy"] = settings.isotropy;
  parameters["axis"] = std::string(1, "ijk"[settings.axis]);
  parameters["block_size"] = settings.block_size;
  parameters["mode"] = to_string(settings.mode);
  parameters["extended_time_lag"] = settings.extended_time_lag;
  parameters["source"] = volume.source();
  // What decides the components. The store refuses a run of another identity (it would mix
  // two extractions); a rerun of the same one resumes.
  parameters["identity"] = {
      {"iso", std::strtod(number_text(settings.iso).c_str(), nullptr)}, // 0.6f recorded as 0.6
      {"max_error", settings.max_error},
      {"isotropy", settings.isotropy},
      {"axis", parameters["axis"]},
      {"block_size", settings.block_size},
      {"mode", to_string(settings.mode)},
      {"extended_time_lag", settings.extended_time_lag},
      {"input", settings.parameters.contains("input_content") ? settings.parameters["input_content"]
                                                              : volume::input_fingerprint(volume.source())},
      {"chain", settings.parameters.is_object() && settings.parameters.contains("chain") ? settings.parameters["chain"]
                                                                                         : nlohmann::json::object()}};
  // Recorded in the identity only for the low side: stores made before sides existed (all above)
  // keep resuming.
  if (settings.below) parameters["identity"]["side"] = "below";
  // How a command reads its file (a recipe's chain records it): recorded only when given, so that
  // stores made before these keys existed still resume.
  for (const char* key : {"no_data", "variable", "segy"})
    if (settings.parameters.is_object() && settings.parameters.contains(key))
      parameters["identity"][key] = settings.parameters[key];

  return parameters;
}

void warn_if_empty(ExtractResult& result, const ExtractSettings& settings, Logger& log) {
  // An empty result is almost always an isovalue outside the data: say so.
  if (result.components == 0 && result.duplicates == 0) {
    // A recipe's chain that ends in an attribute: the input's range says nothing about it.
    const auto& p = settings.parameters;
    const bool attribute =
        p.is_object() && p.contains("chain") && ChainDescription::from_json(p["chain"]).reads_attribute();
    const std::string warning =
        "no component was extracted: is the isovalue " + number_text(settings.iso) +
        (attribute ? " inside the attribute's value range? (write the attribute with output.attribute in the recipe "
                     "and see its range with 'geotandem info' on that file)"
                   : " inside the cube's value range? ('geotandem info' on the cube shows it)");
    log.warning(warning);
    result.statistics["warnings"] = {warning};
  }
}

std::string copy_input_for_blocks(const volume::Volume& input, const std::string& directory, Logger& log,
                                  Progress& progress, const CancelToken& cancel) {
  try {
    const std::string path = input.use_block_copy(directory, &progress, cancel);
    if (!path.empty())
      log.info("reading " + input.source() + " from its copy " + path +
               " (one pass over the file: its chunks are too large for reads by blocks)");
    return path;
  } catch (const IoError& e) {
    log.warning("cannot copy " + input.source() + " for reads by blocks (" + e.message() +
                "); reading the file as it is, which decodes its chunks many times over");
    std::error_code ec;
    std::filesystem::remove(directory, ec); // when empty: the failed copy left nothing in it
    return {};
  }
}

void remove_input_copy(const std::string& path, Logger& log) {
  if (path.empty()) return;
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::filesystem::remove(path + ".json", ec);
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();
  std::filesystem::remove(directory, ec); // when empty
  log.info("removed the copy of the input " + path);
}

void require_cells(const volume::Geometry& geometry, const std::string& source) {
  static const char* const kAxes[3] = {"inline", "crossline", "sample"};
  const auto& n = geometry.shape;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (n[axis] >= 2) continue;
    throw InvalidArgument(
        "the cube has " + std::to_string(n[axis]) + " sample" + (n[axis] == 1 ? "" : "s") + " along the " +
            kAxes[axis] + " axis (shape " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
            std::to_string(n[2]) + "): an isosurface needs at least 2 samples along each axis",
        {source}, "a single inline, crossline or time slice is a 2-D section; extract from a 3-D cube");
  }
}

ExtractResult extract_to_store(const volume::Volume& volume, store::ComponentStore& store,
                               const ExtractSettings& settings, Logger& log, Progress& progress,
                               const CancelToken& cancel) {
  require_cells(volume.geometry(), {});
  if (!(store.geometry() == volume.geometry()))
    throw InvalidArgument("the store was made for another cube geometry", {store.directory().string()},
                          "extract into a new store directory");
  if (settings.block_size != 0 && settings.block_size < min_block_size)
    throw InvalidArgument("block size must be 0 (one block) or at least " + std::to_string(min_block_size) +
                              " cells, got " + std::to_string(settings.block_size),
                          {}, "blocks of 64 to 256 cells are typical");
  if (settings.workers > 0) return extract_with_workers(volume, store, settings, log, progress, cancel);
  auto start = std::chrono::steady_clock::now();
  tandem::TandemOptions options;
  options.iso = settings.iso;
  options.below = settings.below;
  options.axis = settings.axis;
  options.simplify.max_error = settings.max_error;
  options.simplify.isotropy = settings.isotropy;
  options.simplify.extended_time_lag = settings.extended_time_lag;
  options.simplify.validate();
  options.dump = settings.mode != ExtractMode::tandem;
  options.cancel = &cancel;
  options.progress = &progress;

  const nlohmann::json parameters = extract_run_parameters(volume, settings);

  ExtractResult result;
  result.run = store.begin_run(parameters.dump());
  store::LocalSinkOptions sink_options;
  sink_options.run = result.run;
  store::LocalSink sink(store, sink_options);
  log.info("extracting in this process, on one core");

  // One block (block_size 0), or the block tree: leaves one after the other, brothers merged
  // bottom-up, each partial surface through its wire form as the runtime will ship it.
  const volume::Box cells = tandem::cube_cells(volume.geometry().shape);
  const bool brute = settings.mode == ExtractMode::brute;
  tandem::BlocksStats blocks;
  if (settings.block_size > 0) {
    log.info("block tree with leaves of at most " + std::to_string(settings.block_size) + " cells per axis");
    blocks = tandem::extract_blocks(volume, cells, settings.block_size, options, &sink, nullptr, brute);
  } else {
    blocks.tandem = tandem::extract_block(volume, cells, options, &sink, nullptr, brute);
    blocks.leaves = 1;
  }
  sink.close();
  const tandem::TandemStats& stats = blocks.tandem;

  // A repaired component's row replaces the damaged one: counted as repaired, not as a new key.
  result.repaired = sink.redone();
  result.repaired_keys = sink.redone_keys();
  result.components = sink.committed() - std::min(sink.committed(), result.repaired);
  result.duplicates = sink.duplicates();
  double extract_s = 0, insert_s = 0, simplify_s = 0, dump_s = 0;
  for (const auto& layer : stats.layers) { // with blocks: every leaf's layers in tree order
    result.triangles_per_layer.push_back(layer.triangles_in_memory);
    extract_s += layer.seconds_extract;
    insert_s += layer.seconds_insert;
    simplify_s += layer.seconds_simplify;
    dump_s += layer.seconds_dump;
  }
  simplify_s += stats.final_pass.seconds_simplify;
  dump_s += stats.final_pass.seconds_dump;
  result.counters = stats.counters; // leaves, seams and the final pass
  result.peak_triangles = stats.peak_triangles;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_kb = peak_rss_kb();
  result.blocks = {
      {"block_size", settings.block_size},
      {"leaves", blocks.leaves},
      {"merges", blocks.merges},
      {"seam_collapses", blocks.seam_collapses},
      {"components_at_merges", blocks.components_at_merges},
      {"peak_held_triangles", blocks.peak_held_triangles},
      {"wire_bytes", blocks.wire_bytes},
      {"largest_record", blocks.largest_record},
      {"seconds", {{"leaves", blocks.seconds_leaves}, {"wire", blocks.seconds_wire}, {"merge", blocks.seconds_merge}}}};
  result.statistics = {{"components", result.components},
                       {"duplicates", result.duplicates},
                       {"repaired", result.repaired},
                       {"input_triangles", result.counters.input_triangles},
                       {"peak_triangles", result.peak_triangles},
                       {"collapses", result.counters.collapses},
                       {"counters", nlohmann::json::parse(runtime::counters_to_json(result.counters))},
                       {"triangles_per_layer", result.triangles_per_layer},
                       {"blocks", result.blocks},
                       {"seconds",
                        {{"total", result.seconds},
                         {"marching_cubes", extract_s},
                         {"insert", insert_s},
                         {"simplify", simplify_s},
                         {"dump", dump_s}}},
                       {"peak_rss_kb", result.peak_rss_kb}};
  warn_if_empty(result, settings, log);
  store.end_run(result.run, result.statistics.dump());
  return result;
}

} // namespace geotandem::workflow
