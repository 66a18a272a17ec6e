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
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// The trace index (Grid::traces) as base64 of little-endian 32-bit integers.
std::string encode_index(const std::vector<std::int32_t>& traces) {
  std::string bytes(traces.size() * 4, '\0');
  for (std::size_t n = 0; n < traces.size(); ++n) {
    const auto v = static_cast<std::uint32_t>(traces[n]);
    for (int b = 0; b < 4; ++b)
      bytes[4 * n + static_cast<std::size_t>(b)] = static_cast<char>((v >> (8 * b)) & 0xFF);
  }
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t n = 0; n < bytes.size(); n += 3) {
    std::uint32_t chunk = static_cast<unsigned char>(bytes[n]) << 16;
    if (n + 1 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[n + 1]) << 8;
    if (n + 2 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[n + 2]);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += n + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += n + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

// Nothing when the text is not the base64 of `count` integers.
std::optional<std::vector<std::int32_t>> decode_index(const std::string& text, std::size_t count) {
  if (text.size() != (count * 4 + 2) / 3 * 4) return std::nullopt;
  std::array<int, 256> digit{};
  digit.fill(-1);
  for (int n = 0; n < 64; ++n)
    digit[static_cast<unsigned char>(kAlphabet[n])] = n;
  std::vector<unsigned char> bytes;
  bytes.reserve(count * 4 + 2);
  for (std::size_t n = 0; n < text.size(); n += 4) {
    std::uint32_t chunk = 0;
    int pad = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[n + k];
      if (c == '=') {
        ++pad;
        chunk <<= 6;
        continue;
      }
      const int d = digit[static_cast<unsigned char>(c)];
      if (d < 0 || pad > 0) return std::nullopt;
      chunk = chunk << 6 | static_cast<std::uint32_t>(d);
    }
    bytes.push_back(static_cast<unsigned char>(chunk >> 16));
    if (pad < 2) bytes.push_back(static_cast<unsigned char>(chunk >> 8));
    if (pad < 1) bytes.push_back(static_cast<unsigned char>(chunk));
  }
  if (bytes.size() != count * 4) return std::nullopt;
  std::vector<std::int32_t> traces(count);
  for (std::size_t n = 0; n < count; ++n)
    traces[n] =
        static_cast<std::int32_t>(std::uint32_t{bytes[4 * n]} | std::uint32_t{bytes[4 * n + 1]} << 8 |
                                  std::uint32_t{bytes[4 * n + 2]} << 16 | std::uint32_t{bytes[4 * n + 3]} << 24);
  return traces;
}

// An index sent whole weighs 5.3 bytes per bin: beyond this many bins, workers read the headers.
constexpr std::size_t kMaxIndexBins = std::size_t{16} << 20;

} // namespace

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
  // Holes everywhere, or traces in no order, make runs of a trace or two: the index itself is sent
  // (base64 of 4 bytes per bin), unless the survey is huge: each worker then reads the headers.
  std::string index;
  if (runs.size() > std::max<std::size_t>(1024, bin_of.size() / 16)) {
    if (g.traces.size() > kMaxIndexBins) return {};
    runs = nlohmann::json::array();
    index = encode_index(g.traces);
  }
  const SurveyAffine& a = g.fitted_affine;
  return nlohmann::json{{"segy_grid",
                         {{"size", stamp.size},
                          {"modified_ns", stamp.modified_ns},
                          {"options", to_json(g.bytes)},
                          {"inline_sorted", g.inline_sorted},
                          {"unsorted", g.unsorted},
                          {"index", index},
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
        h.at("modified_ns").get<std::int64_t>() != stamp.modified_ns || h.at("options") != to_json(bytes))
      return std::nullopt;
    Grid g;
    g.bytes = bytes;
    g.inline_sorted = h.at("inline_sorted").get<bool>();
    g.unsorted = h.at("unsorted").get<bool>();
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
    if (const std::string& index = h.at("index").get_ref<const std::string&>(); !index.empty()) {
      auto traces_of = decode_index(index, static_cast<std::size_t>(bins));
      if (!traces_of) return std::nullopt;
      // Each of the file's traces at most once, the placeholders left out and no other.
      std::vector<bool> seen(static_cast<std::size_t>(traces), false);
      std::int64_t placed = 0;
      for (const std::int32_t t : *traces_of) {
        if (t < -1 || t >= traces) return std::nullopt;
        if (t < 0) continue;
        if (seen[static_cast<std::size_t>(t)]) return std::nullopt;
        seen[static_cast<std::size_t>(t)] = true;
        ++placed;
      }
      if (placed != traces - g.placeholders_left_out || g.first_live < 0 || g.first_live >= traces ||
          !seen[static_cast<std::size_t>(g.first_live)])
        return std::nullopt;
      g.traces = std::move(*traces_of);
      return g;
    }
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
