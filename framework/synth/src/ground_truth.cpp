#include "geotandem/synth/ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/geometry_json.hpp"

namespace geotandem::synth {
namespace {

// JSON has no infinity: an infinite SNR (no noise) is written as null.
nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json truth_geometry_json(const volume::Geometry& g) {
  nlohmann::json j = volume::geometry_fields_json(g);
  j["shape"] = {g.shape[0], g.shape[1], g.shape[2]};
  j["axes"] = {"inline", "crossline", "sample"};
  j["bin_size_m"] = {g.affine.step_i(), g.affine.step_j()};
  return j;
}

nlohmann::json body_json(const Body& b) {
  nlohmann::json dims = nlohmann::json::object();
  for (const auto& [name, value] : b.dimensions)
    dims[name] = value;
  return {{"name", b.name},
          {"type", to_string(b.type)},
          {"centre_index", b.centre_index},
          {"centre_world", b.centre_world},
          {"azimuth_deg", b.azimuth_deg},
          {"volume_voxels", b.volume_voxels},
          {"volume_world", b.volume_world},
          {"volume_exact", b.volume_exact},
          {"bounds_index", {{"lo", b.bounds_lo}, {"hi", b.bounds_hi}}},
          {"dimensions", dims},
          {"crosses_block_plane", b.crosses_block_plane},
          {"cut_by_border", b.cut_by_border},
          {"has_cavity", b.has_cavity},
          {"chaotic", b.chaotic},
          {"negative_control", b.negative_control}};
}

} // namespace

const char* to_string(CubeKind kind) {
  return kind == CubeKind::analytic ? "analytic" : "seismic";
}

CubeKind parse_cube_kind(const std::string& text) {
  if (text == "analytic") return CubeKind::analytic;
  if (text == "seismic") return CubeKind::seismic;
  throw InvalidArgument("unknown synthetic cube kind '" + text + "'", {},
                        "use 'analytic' (attribute-like field with exact bodies) or 'seismic' (convolutional model)");
}

const char* to_string(BodyType type) {
  switch (type) {
  case BodyType::ellipsoid: return "ellipsoid";
  case BodyType::tube: return "tube";
  case BodyType::shell: return "shell";
  case BodyType::channel: return "channel";
  case BodyType::lobe: return "lobe";
  case BodyType::bright_spot: return "bright_spot";
  }
  return "unknown";
}

namespace {

// Everything but the bodies, which are an empty array.
nlohmann::json header_json(const GroundTruth& t) {
  nlohmann::json j;
  j["format"] = "geotandem synthetic ground truth";
  j["version"] = 1;
  j["kind"] = to_string(t.kind);
  j["seed"] = t.seed;
  j["geometry"] = truth_geometry_json(t.geometry);
  j["world_volume_unit"] = t.world_volume_unit;
  j["body_frame_unit_m"] = t.body_frame_unit_m;
  j["voxel_volume_world"] = t.voxel_volume_world;
  j["iso"] = t.iso ? nlohmann::json(*t.iso) : nlohmann::json(nullptr);
  j["bubble_volume_threshold"] = {{"voxels", t.bubble_volume_threshold_voxels},
                                  {"world", t.bubble_volume_threshold_voxels * t.voxel_volume_world}};
  j["bubbles"] = {{"count", t.bubble_count}, {"radius_min", t.bubble_radius_min}, {"radius_max", t.bubble_radius_max}};
  j["block_planes"] = {{"inline", t.block_planes[0]}, {"crossline", t.block_planes[1]}, {"sample", t.block_planes[2]}};
  j["bodies"] = nlohmann::json::array();
  if (t.seismic) {
    const auto& s = *t.seismic;
    j["seismic"] = {{"peak_frequency_hz", s.peak_frequency_hz},
                    {"snr", finite_or_null(s.snr)},
                    {"signal_rms", s.signal_rms},
                    {"noise_rms", s.noise_rms},
                    {"background_rms", s.background_rms},
                    {"chaotic_rms", s.chaotic_rms},
                    {"wavelet_half_length", s.wavelet_half_length},
                    {"rms_threshold_suggestion", s.rms_threshold_suggestion}};
  }
  return j;
}

} // namespace

nlohmann::json to_json(const GroundTruth& t) {
  nlohmann::json j = header_json(t);
  nlohmann::json& bodies = j["bodies"];
  for (const auto& b : t.bodies)
    bodies.push_back(body_json(b));
  return j;
}

void write_ground_truth(const GroundTruth& truth, const std::string& path) {
  // Renamed into place when whole (AtomicFile): two runs writing one truth.json never interleave.
  AtomicFile file(path);
  std::ostream& out = file.stream();
  // The same text as to_json(truth).dump(2), written body by body. The whole document of a large
  // cube (21,317 bodies and 23 MB of text for the analytic 1024^3) took about 150 MB in small
  // blocks, which glibc's heap kept resident after they were freed, under the extraction that
  // followed.
  const std::string header = header_json(truth).dump(2);
  const std::string empty = "\"bodies\": []";
  const std::size_t at = header.find(empty);
  if (truth.bodies.empty() || at == std::string::npos) {
    out << header << '\n';
  } else {
    out << header.substr(0, at) << "\"bodies\": [";
    // An element of the top object's array is indented by two levels of two spaces.
    for (std::size_t n = 0; n < truth.bodies.size(); ++n) {
      const std::string text = body_json(truth.bodies[n]).dump(2);
      out << (n == 0 ? "\n    " : ",\n    ");
      for (std::size_t from = 0, to; from < text.size(); from = to + 1) {
        to = std::min(text.find('\n', from), text.size());
        out.write(text.data() + from, static_cast<std::streamsize>(to - from));
        if (to < text.size()) out << "\n    ";
      }
    }
    out << "\n  ]" << header.substr(at + empty.size()) << '\n';
  }
  file.commit("the ground-truth file");
}

std::string truth_path_for(const std::string& cube_path) {
  std::string path = cube_path;
  while (path.size() > 1 && path.back() == '/')
    path.pop_back(); // "cube.zarr/" names the same store as "cube.zarr"
  return path + ".truth.json";
}

} // namespace geotandem::synth
