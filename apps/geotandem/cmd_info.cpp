// geotandem info FILE: what a cube is (format, shape, geometry, value range), for people and scripts.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "geotandem/core/params.hpp"
#include "geotandem/volume/io.hpp"

namespace geotandem::app {
namespace {

struct Info {
  std::string path;
  std::string options_nan;
  bool json = false;
  bool no_stats = false;
  std::optional<double> no_data;
  std::string variable;
  volume::SegyOptions segy;
  std::string crs;
};

struct ValueStats {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double sum = 0.0, sum2 = 0.0;
  std::uint64_t count = 0, non_finite = 0;
  std::uint64_t at_min = 0, at_max = 0; // samples holding the minimum, the maximum
  // The nearest values beyond them: a null lies far outside the amplitudes (-999.25 against +-5).
  double next_min = std::numeric_limits<double>::infinity();
  double next_max = -std::numeric_limits<double>::infinity();
};

// Scans the cube by slabs of inlines so that memory stays bounded for any cube size.
ValueStats scan_values(const volume::Volume& cube, Progress& progress, const CancelToken& cancel) {
  const auto& g = cube.geometry();
  std::int64_t slab = std::max<std::int64_t>(1, (64ll << 20) / std::max<std::int64_t>(1, g.shape[1] * g.shape[2] * 4));
  ValueStats s;
  progress.begin("scanning values", static_cast<std::uint64_t>(g.shape[0]), "inlines");
  std::vector<float> buffer;
  for (std::int64_t i = 0; i < g.shape[0]; i += slab) {
    cancel.throw_if_cancelled();
    volume::Box box{{i, 0, 0}, {std::min(g.shape[0], i + slab), g.shape[1], g.shape[2]}};
    buffer.resize(box.count());
    cube.read(box, buffer);
    for (float v : buffer) {
      if (!std::isfinite(v)) {
        ++s.non_finite;
        continue;
      }
      if (v < s.min) {
        s.next_min = s.min;
        s.min = v;
        s.at_min = 0;
      } else if (v > s.min && v < s.next_min) {
        s.next_min = v;
      }
      if (v > s.max) {
        s.next_max = s.max;
        s.max = v;
        s.at_max = 0;
      } else if (v < s.max && v > s.next_max) {
        s.next_max = v;
      }
      s.at_min += v == s.min;
      s.at_max += v == s.max;
      s.sum += v;
      s.sum2 += static_cast<double>(v) * v;
      ++s.count;
    }
    progress.update(static_cast<std::uint64_t>(box.hi[0]));
  }
  progress.end();
  return s;
}

nlohmann::json describe(const volume::Volume& cube, const ValueStats* stats) {
  const auto& g = cube.geometry();
  nlohmann::json j;
  j["source"] = cube.source();
  j["format"] = cube.format();
  // How the file encodes the cube (SEG-Y: sample format, byte order, header bytes used).
  nlohmann::json details = nlohmann::json::object();
  for (const auto& d : cube.format_details())
    details[d.key] = d.value;
  j["details"] = details;
  j["shape"] = {{"inline", g.shape[0]}, {"crossline", g.shape[1]}, {"sample", g.shape[2]}};
  j["inline"] = {
      {"first", g.inline0}, {"step", g.inline_step}, {"last", g.inline0 + g.inline_step * double(g.shape[0] - 1)}};
  j["crossline"] = {{"first", g.crossline0},
                    {"step", g.crossline_step},
                    {"last", g.crossline0 + g.crossline_step * double(g.shape[1] - 1)}};
  j["sample"] = {{"first", g.z0},
                 {"interval", g.dz},
                 {"unit", volume::to_string(g.z_unit)},
                 {"last", g.z0 + g.dz * double(g.shape[2] - 1)}};
  const auto& a = g.affine;
  j["affine"] = {{"x0", a.x0}, {"xi", a.xi}, {"xj", a.xj}, {"y0", a.y0}, {"yi", a.yi}, {"yj", a.yj}};
  j["bin_size_m"] = {a.step_i(), a.step_j()};
  // The CRS of x and y, or "no CRS given" (with x and y then taken as metres).
  if (g.crs.empty())
    j["crs"] = {{"name", volume::kNoCrs}, {"unit", "m"}};
  else
    j["crs"] = {{"name", g.crs.name},
                {"code", g.crs.code},
                {"unit", g.crs.unit},
                {"unit_name", g.crs.unit_name},
                {"wkt", g.crs.wkt}};
  nlohmann::json corners = nlohmann::json::array();
  for (auto [i, jj] : {std::pair{0.0, 0.0},
                       {double(g.shape[0] - 1), 0.0},
                       {0.0, double(g.shape[1] - 1)},
                       {double(g.shape[0] - 1), double(g.shape[1] - 1)}}) {
    auto xy = a.apply(i, jj);
    corners.push_back({{"inline_index", i}, {"crossline_index", jj}, {"x", xy[0]}, {"y", xy[1]}});
  }
  j["corners"] = corners;
  j["samples"] = g.sample_count();
  if (stats) {
    double mean = stats->count ? stats->sum / double(stats->count) : 0.0;
    double var = stats->count ? std::max(0.0, stats->sum2 / double(stats->count) - mean * mean) : 0.0;
    j["values"] = {{"min", stats->count ? stats->min : 0.0},
                   {"max", stats->count ? stats->max : 0.0},
                   {"mean", mean},
                   {"std", std::sqrt(var)},
                   {"non_finite", stats->non_finite},
                   {"at_min", stats->at_min},
                   {"at_max", stats->at_max}};
    // Many samples at an extreme far outside the others' spread: most likely a null value.
    nlohmann::json nulls = nlohmann::json::array();
    const auto lone = [&](double end, double next, double other_end, std::uint64_t at) {
      return std::isfinite(next) && at >= 2 && at * 200 >= stats->count && std::abs(next - end) > other_end - next;
    };
    if (lone(stats->min, stats->next_min, stats->max, stats->at_min))
      nulls.push_back({{"value", stats->min}, {"samples", stats->at_min}});
    if (lone(-stats->max, -stats->next_max, -stats->min, stats->at_max))
      nulls.push_back({{"value", stats->max}, {"samples", stats->at_max}});
    j["values"]["suspected_nulls"] = nulls;
  }
  return j;
}

// `details` in the reader's order (the JSON object sorts its keys).
void print_text(const nlohmann::json& j, const std::vector<volume::FormatDetail>& details) {
  auto& o = std::cout;
  o << "file:       " << j["source"].get<std::string>() << "\n";
  o << "format:     " << j["format"].get<std::string>() << "\n";
  for (const auto& d : details) {
    std::string label = d.key;
    std::replace(label.begin(), label.end(), '_', ' ');
    o << "  " << std::left << std::setw(16) << (label + ":") << std::right << d.value << "\n";
  }
  o << "shape:      " << j["shape"]["inline"] << " inlines x " << j["shape"]["crossline"] << " crosslines x "
    << j["shape"]["sample"] << " samples (" << j["samples"] << " samples)\n";
  o << "inlines:    " << j["inline"]["first"] << " to " << j["inline"]["last"] << " step " << j["inline"]["step"]
    << "\n";
  o << "crosslines: " << j["crossline"]["first"] << " to " << j["crossline"]["last"] << " step "
    << j["crossline"]["step"] << "\n";
  o << "samples:    " << j["sample"]["first"] << " to " << j["sample"]["last"] << " "
    << j["sample"]["unit"].get<std::string>() << ", interval " << j["sample"]["interval"] << "\n";
  const std::string xy = j["crs"]["unit"].get<std::string>();
  if (j["crs"].contains("wkt"))
    o << "crs:        " << j["crs"]["name"].get<std::string>()
      << (j["crs"]["code"].get<std::string>().empty() ? std::string()
                                                      : " (" + j["crs"]["code"].get<std::string>() + ")")
      << ", x and y in " << j["crs"]["unit_name"].get<std::string>() << "\n";
  else
    o << "crs:        " << volume::kNoCrs << " (x and y taken as metres; give one with --crs)\n";
  o << "bins:       " << j["bin_size_m"][0] << " " << xy << " x " << j["bin_size_m"][1] << " " << xy << "\n";
  for (const auto& c : j["corners"])
    o << "corner:     il index " << c["inline_index"] << ", xl index " << c["crossline_index"] << " -> x " << std::fixed
      << std::setprecision(2) << c["x"].get<double>() << ", y " << c["y"].get<double>() << "\n"
      << std::defaultfloat;
  if (j.contains("values")) {
    const auto& v = j["values"];
    o << "values:     min " << v["min"] << ", max " << v["max"] << ", mean " << v["mean"] << ", std " << v["std"];
    if (v["non_finite"].get<std::uint64_t>() > 0)
      o << ", " << v["non_finite"] << " missing samples (NaN, infinite or no data)";
    o << "\n";
    // A null value that a SEG-Y or raw file cannot declare is read as an amplitude: say so.
    const auto count = j["samples"].get<std::uint64_t>() - v["non_finite"].get<std::uint64_t>();
    for (const auto& null : v["suspected_nulls"]) {
      const auto at = null["samples"].get<std::uint64_t>();
      const std::string value = number_text(null["value"].get<float>()); // a sample's value
      o << "note:       " << at << " samples (" << std::fixed << std::setprecision(1)
        << 100.0 * double(at) / double(count) << std::defaultfloat << " %) hold " << value
        << ", far outside the other values: a null? If they mark missing data, pass --no-data " << value
        << " (input.no_data in a recipe)\n";
    }
  }
}

} // namespace

void add_info_command(CLI::App& app, Context& context, Runner& run) {
  auto info = std::make_shared<Info>();
  auto* cmd = app.add_subcommand("info", "Describe a cube: format, shape, geometry and value range.");
  cmd->add_option("file", info->path, "the cube (netCDF, HDF5, Zarr, GeoTIFF, ENVI, SEG-Y, raw+json)")->required();
  cmd->add_flag("--json", info->json, "print JSON for scripts instead of text");
  cmd->add_flag("--no-stats", info->no_stats, "skip the value scan (fast on huge cubes)");
  cmd->add_option("--no-data", info->no_data,
                  "samples of this value are missing too, as NaN samples are: counted with them and left out of "
                  "the statistics (a SEG-Y or raw cube's null, often -999.25)")
      ->type_name("VALUE");
  add_cube_reading_options(*cmd, info->variable, info->segy);
  add_crs_option(*cmd, info->crs);
  cmd->callback([info, &context, &run] {
    run = [info, &context] {
      volume::OpenOptions options;
      options.crs = crs_option(info->crs);
      options.nan_policy = volume::NanPolicy::fill; // info reports non-finite samples instead of failing
      options.fill_value = std::numeric_limits<float>::quiet_NaN();
      options.segy = info->segy;
      options.variable = info->variable;
      options.no_data = no_data_option(info->no_data);
      auto opening = context.progress(); // an irregular SEG-Y survey's pass over its headers
      options.progress = opening.get();
      auto cube = volume::open_volume(info->path, options);
      std::optional<ValueStats> stats;
      if (!info->no_stats) {
        auto progress = context.progress();
        stats = scan_values(*cube, *progress, context.cancel);
      }
      auto j = describe(*cube, stats ? &*stats : nullptr);
      if (info->json)
        std::cout << j.dump(2) << "\n";
      else
        print_text(j, cube->format_details());
      return 0;
    };
  });
}

} // namespace geotandem::app
