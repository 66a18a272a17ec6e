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
#include "geotandem/volume/geometry_json.hpp"
#include "geotandem/workflow/chain.hpp"

namespace geotandem::workflow {

const std::vector<ParamSpec>& extract_params() {
  return tandem::extraction_params();
}

std::int64_t peak_rss_kb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6));
  return 0;
}

nlohmann::json extract_run_parameters(const volume::Volume& volume, const ExtractionOptions& options,
                                      const ExecutionContext& context) {
  const nlohmann::json& record = context.record;
  nlohmann::json parameters = record.is_object() ? record : nlohmann::json::object();
  const nlohmann::json codec = tandem::to_json(options); // the options as SETUP carries them
  parameters.update(codec);
  parameters["source"] = volume.source();
  // The CRS of the map coordinates: kept with the run, outside its identity (it changes no
  // component; the store refuses a run that names another CRS than its own).
  const volume::Crs& crs = volume.geometry().crs;
  parameters["crs"] = crs.empty() ? nlohmann::json(volume::kNoCrs) : nlohmann::json(volume::crs_json(crs));
  // What decides the components. The store refuses a run of another identity (it would mix
  // two extractions); a rerun of the same one resumes.
  parameters["identity"] = codec;
  // The side is part of the identity only when it is below: stores made before sides existed (all
  // above) keep their identity and resume.
  if (options.side == tandem::Side::above) parameters["identity"].erase("side");
  parameters["identity"]["input"] =
      parameters.contains("input_content") ? record["input_content"] : volume::input_fingerprint(volume.source());
  parameters["identity"]["chain"] = parameters.contains("chain") ? record["chain"] : nlohmann::json::object();
  // How a command reads its file (a recipe's chain records it): recorded only when given, so that
  // stores made before these keys existed still resume.
  for (const char* key : {"no_data", "variable", "segy"})
    if (parameters.contains(key)) parameters["identity"][key] = record[key];
  return parameters;
}

void warn_if_empty(ExtractResult& result, const ExtractionOptions& options, const ExecutionContext& context,
                   Logger& log) {
  // An empty result is almost always an isovalue outside the data: say so.
  if (result.components == 0 && result.duplicates == 0) {
    // A recipe's chain that ends in an attribute: the input's range says nothing about it.
    const auto& p = context.record;
    const bool attribute =
        p.is_object() && p.contains("chain") && ChainDescription::from_json(p["chain"]).reads_attribute();
    const std::string warning =
        "no component was extracted: is the isovalue " + number_text(options.iso) +
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
                               const ExtractionOptions& extraction, const ExecutionContext& context, Logger& log,
                               Progress& progress, const CancelToken& cancel) {
  require_cells(volume.geometry(), {});
  if (!store.geometry().same_grid(volume.geometry()))
    throw InvalidArgument("the store was made for another cube geometry", {store.directory().string()},
                          "extract into a new store directory");
  extraction.validate(); // block_size 0 or at least min_block_size, every value in its range
  if (context.workers > 0) return extract_with_workers(volume, store, extraction, context, log, progress, cancel);
  auto start = std::chrono::steady_clock::now();
  tandem::TandemOptions options = tandem::loop_options(extraction);
  options.simplify.validate();
  options.cancel = &cancel;
  options.progress = &progress;

  const nlohmann::json parameters = extract_run_parameters(volume, extraction, context);

  ExtractResult result;
  result.run = store.begin_run(parameters.dump());
  store::LocalSinkOptions sink_options;
  sink_options.run = result.run;
  store::LocalSink sink(store, sink_options);
  log.info("extracting in this process, on one core");

  // One block (block_size 0), or the block tree: leaves one after the other, brothers merged
  // bottom-up, each partial surface through its wire form as the runtime will ship it.
  const volume::Box cells = tandem::cube_cells(volume.geometry().shape);
  const bool brute = extraction.mode == ExtractMode::brute;
  tandem::BlocksStats blocks;
  if (extraction.block_size > 0) {
    log.info("block tree with leaves of at most " + std::to_string(extraction.block_size) + " cells per axis");
    blocks = tandem::extract_blocks(volume, cells, extraction.block_size, options, &sink, nullptr, brute);
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
      {"block_size", extraction.block_size},
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
  warn_if_empty(result, extraction, context, log);
  store.end_run(result.run, result.statistics.dump());
  return result;
}

} // namespace geotandem::workflow
