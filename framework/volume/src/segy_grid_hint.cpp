#include "segy_grid_hint.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail::segy {

FileStamp file_stamp(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw IoError(std::string("cannot examine the file: ") + std::strerror(errno), {path});
  return {static_cast<std::uintmax_t>(st.st_size),
          static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
}

std::string grid_hint(const Grid& g, const FileStamp& stamp) {
  if (!g.fitted) return {}; // found from a few headers: nothing to spare
  // Each trace's bin (row-major), in file order; then runs of traces whose bins go on by a constant
  // step: [first trace, its bin, count, step] (step 1 or nj along a line, negative for numbers that
  // count down).
  std::vector<std::int64_t> bin_of;
  for (std::size_t b = 0; b < g.traces.size(); ++b)
    if (const std::int32_t t = g.traces[b]; t >= 0) {
      if (bin_of.size() <= static_cast<std::size_t>(t)) bin_of.resize(static_cast<std::size_t>(t) + 1, -1);
      bin_of[static_cast<std::size_t>(t)] = static_cast<std::int64_t>(b);
    }
  nlohmann::json runs = nlohmann::json::array();
  for (std::size_t t = 0; t < bin_of.size();) {
    if (bin_of[t] < 0) { // a placeholder left out
      ++t;
      continue;
    }
    const std::int64_t step = t + 1 < bin_of.size() ? bin_of[t + 1] - bin_of[t] : 1;
    std::size_t n = 1;
    while (t + n < bin_of.size() && bin_of[t + n] >= 0 && bin_of[t + n] - bin_of[t + n - 1] == step)
      ++n;
    runs.push_back({t, bin_of[t], n, n > 1 ? step : 1});
    t += n;
  }
  // Holes everywhere make runs of a trace or two: the hint would weigh about as much as the headers
  // it spares each worker, so there is none.
  if (runs.size() > std::max<std::size_t>(1024, bin_of.size() / 16)) return {};
  const SurveyAffine& a = g.fitted_affine;
  return nlohmann::json{{"segy_grid",
                         {{"size", stamp.size},
                          {"modified_ns", stamp.modified_ns},
                          {"bytes", {g.bytes.inline_byte, g.bytes.crossline_byte}},
                          {"inline_sorted", g.inline_sorted},
                          {"lines", {g.ni, g.nj, g.il0, g.il_step, g.xl0, g.xl_step}},
                          {"first_live", g.first_live},
                          {"placeholders_left_out", g.placeholders_left_out},
                          {"affine", {a.x0, a.xi, a.xj, a.y0, a.yi, a.yj}},
                          {"runs", std::move(runs)}}}}
      .dump();
}

std::optional<Grid> grid_from_hint(const std::string& hint, const FileStamp& stamp, const SegyOptions& bytes,
                                   int traces) {
  try {
    const nlohmann::json h = nlohmann::json::parse(hint).at("segy_grid");
    if (h.at("size").get<std::uintmax_t>() != stamp.size ||
        h.at("modified_ns").get<std::int64_t>() != stamp.modified_ns ||
        h.at("bytes") != nlohmann::json{bytes.inline_byte, bytes.crossline_byte})
      return std::nullopt;
    Grid g;
    g.bytes = bytes;
    g.inline_sorted = h.at("inline_sorted").get<bool>();
    const auto lines = h.at("lines").get<std::array<int, 6>>();
    g.ni = lines[0];
    g.nj = lines[1];
    g.il0 = lines[2];
    g.il_step = lines[3];
    g.xl0 = lines[4];
    g.xl_step = lines[5];
    const auto a = h.at("affine").get<std::array<double, 6>>();
    g.fitted = true;
    g.fitted_affine = {a[0], a[1], a[2], a[3], a[4], a[5]};
    g.first_live = h.at("first_live").get<int>();
    g.placeholders_left_out = h.at("placeholders_left_out").get<int>();
    const std::int64_t bins = std::int64_t{g.ni} * g.nj;
    if (g.ni < 1 || g.nj < 1 || g.il_step == 0 || g.xl_step == 0 || bins > 10 * std::int64_t{traces} ||
        bins > std::numeric_limits<std::int32_t>::max())
      return std::nullopt;
    const nlohmann::json& runs = h.at("runs");
    if (runs.empty()) { // a full grid padded with placeholders: the traces follow from the sorting
      if (bins != traces || g.placeholders_left_out != 0 || g.first_live < 0 || g.first_live >= traces)
        return std::nullopt;
      return g;
    }
    g.traces.assign(static_cast<std::size_t>(bins), -1);
    std::int64_t placed = 0, next = 0;
    for (const auto& run : runs) {
      const auto [t, b, n, step] = run.get<std::array<std::int64_t, 4>>();
      // Runs take the file's traces in order (placeholders left out between them), each trace
      // once, each bin at most once.
      if (t < next || n < 1 || n > traces - t || step < -bins || step > bins) return std::nullopt;
      for (std::int64_t m = 0; m < n; ++m) {
        const std::int64_t bin = b + m * step;
        if (bin < 0 || bin >= bins || g.traces[static_cast<std::size_t>(bin)] >= 0) return std::nullopt;
        g.traces[static_cast<std::size_t>(bin)] = static_cast<std::int32_t>(t + m);
      }
      placed += n;
      next = t + n;
    }
    // Every trace but the placeholders left out, the first live one among them.
    if (placed != traces - g.placeholders_left_out || g.first_live < 0 || g.first_live >= traces ||
        std::find(g.traces.begin(), g.traces.end(), g.first_live) == g.traces.end())
      return std::nullopt;
    return g;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

} // namespace geotandem::volume::detail::segy
