// geotandem synth: writes a procedural synthetic cube (analytic attribute field or convolutional
// seismic) and its ground truth (CUBE.truth.json) for tests, demos and benchmarks.

#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/output_path.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/io.hpp"

namespace geotandem::app {
namespace {

struct Synth {
  std::string kind = "analytic";
  std::vector<std::int64_t> shape{128, 128, 128};
  std::uint64_t seed = 1;
  std::string out;
  std::optional<double> snr;
  std::optional<double> frequency;
  bool overwrite = false;
};

std::unique_ptr<synth::SyntheticCube> make_cube(const Synth& s) {
  const volume::Index3 shape{s.shape[0], s.shape[1], s.shape[2]};
  if (synth::parse_cube_kind(s.kind) == synth::CubeKind::analytic) {
    if (s.snr || s.frequency)
      throw InvalidArgument(std::string(s.snr ? "--snr" : "--frequency") + " applies to seismic cubes only", {},
                            "drop it, or pass --kind seismic");
    synth::AnalyticOptions options;
    options.shape = shape;
    options.seed = s.seed;
    return synth::make_analytic(options);
  }
  synth::SeismicOptions options;
  options.shape = shape;
  options.seed = s.seed;
  if (s.snr) options.snr = *s.snr;
  if (s.frequency) options.peak_frequency_hz = *s.frequency;
  return synth::make_seismic(options);
}

// "3 tubes, 1 shell" from the body types, in a fixed order.
std::string count_types(const synth::GroundTruth& truth) {
  std::map<std::string, int> counts;
  for (const auto& b : truth.bodies)
    ++counts[synth::to_string(b.type)];
  std::string text;
  for (const auto& [type, n] : counts) {
    if (!text.empty()) text += ", ";
    std::string name = type == "bright_spot" ? "bright spot" : type;
    text += std::to_string(n) + " " + name + (n == 1 ? "" : (name.back() == 'h' ? "es" : "s"));
  }
  return text;
}

std::string describe(const synth::SyntheticCube& cube, const std::string& out, const std::string& truth_path) {
  const auto& t = cube.truth();
  const auto& g = t.geometry;
  int crossing = 0, cut = 0;
  for (const auto& b : t.bodies) {
    crossing += b.crosses_block_plane;
    cut += b.cut_by_border;
  }
  std::ostringstream text;
  text << "Wrote a synthetic " << synth::to_string(t.kind) << " cube of " << g.shape[0] << " x " << g.shape[1] << " x "
       << g.shape[2] << " samples (seed " << t.seed << ", " << g.affine.step_i() << " m x " << g.affine.step_j()
       << " m bins, dz " << g.dz << " " << volume::to_string(g.z_unit) << ") to " << out << ". It holds "
       << t.bodies.size() << " planted bodies (" << count_types(t) << "): " << crossing
       << " crossing a block plane at 1/4, 1/2 or 3/4 of an axis, " << cut << " cut by the border.";
  if (t.kind == synth::CubeKind::analytic) {
    text << " Bodies are the samples with value >= " << *t.iso << "; " << t.bubble_count
         << " tiny bubbles lie below the bubble volume threshold of " << t.bubble_volume_threshold_voxels
         << " samples.";
  } else {
    const auto& s = *t.seismic;
    text << " Ricker wavelet at " << s.peak_frequency_hz << " Hz, SNR " << s.snr
         << "; channels and lobes are chaotic, the bright spot is a negative control; a starting threshold for an "
            "RMS-amplitude attribute is "
         << s.rms_threshold_suggestion << ".";
  }
  text << " The ground truth (centres, azimuths, volumes, flags) is in " << truth_path << ".";
  return text.str();
}

} // namespace

void add_synth_command(CLI::App& app, Context& context, Runner& run) {
  auto s = std::make_shared<Synth>();
  auto* cmd = app.add_subcommand("synth", "Write a synthetic cube with planted geobodies and its ground truth.");
  cmd->add_option("--kind", s->kind, "analytic (attribute field, exact bodies) or seismic (convolutional model)")
      ->capture_default_str()
      ->check(CLI::IsMember({"analytic", "seismic"}));
  cmd->add_option("--shape", s->shape,
                  "inline, crossline and sample counts (each at least " + std::to_string(synth::min_edge) + ")")
      ->expected(3)
      ->capture_default_str();
  cmd->add_option("--seed", s->seed, "random seed; the same seed and shape give the same cube")
      ->capture_default_str()
      ->check(not_negative());
  cmd->add_option("--out", s->out, "output cube; the format comes from the extension (.nc, .zarr, .tif, .segy, .raw)")
      ->required();
  cmd->add_option("--snr", s->snr, "seismic: RMS signal / RMS noise (> 0, default 4)");
  cmd->add_option("--frequency", s->frequency, "seismic: Ricker peak frequency in Hz (default 30)");
  cmd->add_flag("--overwrite", s->overwrite, "replace an existing output and ground truth");
  cmd->callback([s, &context, &run] {
    run = [s, &context] {
      auto cube = make_cube(*s);
      const std::string truth_path = synth::truth_path_for(s->out);
      std::error_code ec;
      if (!s->overwrite && std::filesystem::exists(truth_path, ec))
        throw IoError("the ground-truth file already exists", {truth_path}, "remove it or pass --overwrite");
      require_replaceable(truth_path);
      volume::WriteOptions options;
      options.overwrite = s->overwrite;
      auto progress = context.progress();
      volume::write_volume(*cube, s->out, options, progress.get(), context.cancel);
      synth::write_ground_truth(cube->truth(), truth_path);
      std::cout << describe(*cube, s->out, truth_path) << "\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
