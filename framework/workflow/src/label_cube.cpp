// The label cube (label_cube.hpp): two passes over slabs of whole inlines, a 6-connected labelling
// of each slab and a union-find across slabs. See docs/label-cube.md.

#include "geotandem/workflow/label_cube.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include <unistd.h>

#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/output_path.hpp"
#include "geotandem/volume/io.hpp"

namespace geotandem::workflow {

namespace fs = std::filesystem;
using volume::Box;

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// Body IDs are float32 samples: exact integers up to 2^24.
constexpr std::uint64_t kMaxBodies = std::uint64_t{1} << 24;

// Inside exactly as marching cubes decides it (LayerExtractor::Impl::read): the low side compares
// the negated value with the negated iso; NaN is outside on both sides.
void inside_of(const std::vector<float>& values, const LabelSettings& s, std::vector<std::uint8_t>& inside) {
  const float iso = s.below ? -s.iso : s.iso;
  const float sign = s.below ? -1.0f : 1.0f;
  inside.resize(values.size());
  for (std::size_t n = 0; n < values.size(); ++n)
    inside[n] = static_cast<std::uint8_t>(sign * values[n] >= iso);
}

// Union-find over int32 labels: the smaller root survives (deterministic), path halving.
class UnionFind {
public:
  void clear() { parent_.clear(); }
  std::int32_t make() {
    parent_.push_back(static_cast<std::int32_t>(parent_.size()));
    return parent_.back();
  }
  std::int32_t find(std::int32_t x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      auto& p = parent_[static_cast<std::size_t>(x)];
      p = parent_[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }
  std::int32_t unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return a;
    if (b < a) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;
    return a;
  }
  std::size_t size() const { return parent_.size(); }

private:
  std::vector<std::int32_t> parent_;
};

// 6-connected components of the inside samples of a slab of `t` inlines of nj x nk samples:
// label[n] in 0..count-1 (numbered in the C order of their first sample), -1 outside. A function
// of the slab's inside samples alone, so both passes number a slab's components alike.
std::int32_t label_slab(const std::vector<std::uint8_t>& inside, std::int64_t t, std::int64_t nj, std::int64_t nk,
                        std::vector<std::int32_t>& label, UnionFind& uf) {
  const std::int64_t plane = nj * nk;
  label.assign(inside.size(), -1);
  uf.clear();
  std::int64_t n = 0;
  for (std::int64_t a = 0; a < t; ++a)
    for (std::int64_t j = 0; j < nj; ++j)
      for (std::int64_t k = 0; k < nk; ++k, ++n) {
        if (!inside[static_cast<std::size_t>(n)]) continue;
        std::int32_t l = -1;
        if (k > 0 && inside[static_cast<std::size_t>(n - 1)]) l = label[static_cast<std::size_t>(n - 1)];
        if (j > 0 && inside[static_cast<std::size_t>(n - nk)]) {
          const std::int32_t m = label[static_cast<std::size_t>(n - nk)];
          l = l < 0 ? m : uf.unite(l, m);
        }
        if (a > 0 && inside[static_cast<std::size_t>(n - plane)]) {
          const std::int32_t m = label[static_cast<std::size_t>(n - plane)];
          l = l < 0 ? m : uf.unite(l, m);
        }
        label[static_cast<std::size_t>(n)] = l < 0 ? uf.make() : l;
      }
  std::vector<std::int32_t> compact(uf.size(), -1);
  std::int32_t count = 0;
  for (auto& l : label) {
    if (l < 0) continue;
    const std::int32_t r = uf.find(l);
    if (compact[static_cast<std::size_t>(r)] < 0) compact[static_cast<std::size_t>(r)] = count++;
    l = compact[static_cast<std::size_t>(r)];
  }
  return count;
}

std::string key_text(std::uint64_t key) {
  return std::to_string(key);
}

} // namespace

struct LabelCube::Impl {
  std::shared_ptr<const volume::Volume> field;
  LabelSettings settings;
  std::int64_t ni = 0, nj = 0, nk = 0, plane = 0, thickness = 1;
  std::vector<std::uint64_t> slab_offset; // first provisional label of each slab
  std::vector<std::uint32_t> final_id;    // provisional label -> body ID (0: no kept body)
  std::vector<LabelledBody> bodies;

  // Pass 2's window: the IDs of inlines [window_lo, window_hi).
  mutable std::int64_t window_lo = 0, window_hi = 0;
  mutable std::vector<std::uint32_t> window;
  mutable std::vector<float> values;
  mutable std::vector<std::uint8_t> inside;
  mutable std::vector<std::int32_t> label;
  mutable UnionFind uf;

  Box slab_box(std::int64_t s) const {
    const std::int64_t a0 = s * thickness, a1 = std::min(ni, a0 + thickness);
    return Box{{a0, 0, 0}, {a1, nj, nk}};
  }
  // Reads and labels slab s into `label`; returns its component count.
  std::int32_t label_of(std::int64_t s) const {
    const Box box = slab_box(s);
    values.resize(box.count());
    field->read(box, values);
    inside_of(values, settings, inside);
    return label_slab(inside, box.size(0), nj, nk, label, uf);
  }
  void first_pass(std::vector<std::uint64_t> keys, Progress& progress, const CancelToken& cancel);
};

void LabelCube::Impl::first_pass(std::vector<std::uint64_t> keys, Progress& progress, const CancelToken& cancel) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const std::uint64_t samples = static_cast<std::uint64_t>(ni) * static_cast<std::uint64_t>(plane);
  // Each key's candidate samples: both ends of its edge (exactly one must be inside), or its cap sample.
  struct Candidate {
    std::uint64_t sample;
    std::uint32_t key;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(2 * keys.size());
  const std::int64_t stride[3] = {plane, nk, 1};
  const std::int64_t shape[3] = {ni, nj, nk};
  for (std::size_t q = 0; q < keys.size(); ++q) {
    const std::uint64_t key = keys[q];
    const auto index = static_cast<std::uint32_t>(q);
    if (key / 3u >= samples) { // a cap vertex: an inside sample on the cube's border
      const std::uint64_t sample = key - 3u * samples;
      if (sample >= samples)
        throw DataError("store key " + key_text(key) + " is no lattice id of this cube's grid", {},
                        "the store was made for another cube");
      candidates.push_back({sample, index});
      continue;
    }
    const std::uint64_t start = key / 3u;
    const int axis = static_cast<int>(key % 3u);
    const std::int64_t along =
        static_cast<std::int64_t>(start / static_cast<std::uint64_t>(stride[axis])) % shape[axis];
    if (along + 1 >= shape[axis])
      throw DataError("store key " + key_text(key) + " names a lattice edge that leaves the cube", {},
                      "the store was made for another cube");
    candidates.push_back({start, index});
    candidates.push_back({start + static_cast<std::uint64_t>(stride[axis]), index});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.sample < b.sample; });

  std::vector<std::uint32_t> parent; // global union-find over provisional labels
  std::vector<std::uint64_t> count;  // samples, summed at roots
  std::vector<std::uint32_t> seed(keys.size(), kNone);
  std::vector<std::uint8_t> hits(keys.size(), 0);
  auto find = [&parent](std::uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  };
  auto unite = [&](std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent[b] = a;
    count[a] += count[b];
  };

  std::vector<std::uint32_t> previous(static_cast<std::size_t>(plane), kNone); // last inline of the previous slab
  const std::int64_t slabs = (ni + thickness - 1) / thickness;
  std::size_t cursor = 0;
  progress.begin("labelling bodies (pass 1 of 2)", static_cast<std::uint64_t>(ni), "inlines");
  for (std::int64_t s = 0; s < slabs; ++s) {
    cancel.throw_if_cancelled();
    const Box box = slab_box(s);
    const std::int32_t found = label_of(s);
    const std::uint64_t offset = parent.size();
    if (offset + static_cast<std::uint64_t>(found) >= kNone)
      throw DataError("the cube has more than 4 billion connected pieces of inside samples per slab", {field->source()},
                      "label a cube with fewer bodies");
    slab_offset.push_back(offset);
    parent.resize(offset + static_cast<std::uint64_t>(found));
    for (std::uint64_t g = offset; g < parent.size(); ++g)
      parent[g] = static_cast<std::uint32_t>(g);
    count.resize(parent.size(), 0);
    for (const std::int32_t l : label)
      if (l >= 0) ++count[offset + static_cast<std::uint64_t>(l)];
    for (std::int64_t m = 0; m < plane; ++m) // joined to the previous slab's last inline (face neighbours)
      if (inside[static_cast<std::size_t>(m)] && previous[static_cast<std::size_t>(m)] != kNone)
        unite(previous[static_cast<std::size_t>(m)],
              static_cast<std::uint32_t>(offset + static_cast<std::uint64_t>(label[static_cast<std::size_t>(m)])));
    const std::uint64_t lo = static_cast<std::uint64_t>(box.lo[0]) * static_cast<std::uint64_t>(plane);
    const std::uint64_t hi = static_cast<std::uint64_t>(box.hi[0]) * static_cast<std::uint64_t>(plane);
    for (; cursor < candidates.size() && candidates[cursor].sample < hi; ++cursor) {
      const auto n = static_cast<std::size_t>(candidates[cursor].sample - lo);
      if (!inside[n]) continue;
      const std::uint32_t q = candidates[cursor].key;
      ++hits[q];
      seed[q] = static_cast<std::uint32_t>(offset + static_cast<std::uint64_t>(label[n]));
    }
    const std::size_t last = static_cast<std::size_t>((box.size(0) - 1) * plane);
    for (std::int64_t m = 0; m < plane; ++m) {
      const std::int32_t l = label[last + static_cast<std::size_t>(m)];
      previous[static_cast<std::size_t>(m)] =
          l < 0 ? kNone : static_cast<std::uint32_t>(offset + static_cast<std::uint64_t>(l));
    }
    progress.update(static_cast<std::uint64_t>(box.hi[0]));
  }
  progress.end();

  for (std::size_t q = 0; q < keys.size(); ++q)
    if (hits[q] != 1)
      throw DataError("store key " + key_text(keys[q]) + (hits[q] == 0 ? " lies on no body" : " lies inside a body") +
                          " of this cube at iso " + std::to_string(settings.iso) + " (side " +
                          (settings.below ? "below" : "above") + "): its lattice edge is not crossed",
                      {field->source()}, "label the cube the store was extracted from, at its iso and side");

  // Bodies: the roots their kept keys seed, numbered in the order of their smallest key.
  std::vector<std::uint32_t> root_id(parent.size(), 0);
  for (std::size_t q = 0; q < keys.size(); ++q) { // keys ascending: a body's first key is its smallest
    const std::uint32_t root = find(seed[q]);
    if (root_id[root] == 0) {
      if (bodies.size() + 1 >= kMaxBodies)
        throw DataError("more than " + std::to_string(kMaxBodies - 1) + " bodies to label", {field->source()},
                        "float32 labels are exact up to 2^24: label a smaller selection");
      bodies.push_back({static_cast<std::uint32_t>(bodies.size() + 1), keys[q], {}, count[root]});
      root_id[root] = bodies.back().id;
    }
    bodies[root_id[root] - 1].keys.push_back(keys[q]);
  }
  std::vector<std::uint64_t>().swap(count);
  final_id.resize(parent.size());
  for (std::uint32_t g = 0; g < parent.size(); ++g)
    final_id[g] = root_id[find(g)];
}

LabelCube::LabelCube(std::shared_ptr<const volume::Volume> field, const LabelSettings& settings,
                     std::vector<std::uint64_t> keys, Progress* progress, const CancelToken& cancel)
    : impl_(std::make_unique<Impl>()) {
  if (std::isnan(settings.iso)) throw InvalidArgument("the label cube's iso is NaN", {field->source()});
  Impl& m = *impl_;
  m.field = std::move(field);
  m.settings = settings;
  const auto& shape = m.field->geometry().shape;
  m.ni = shape[0];
  m.nj = shape[1];
  m.nk = shape[2];
  m.plane = m.nj * m.nk;
  m.thickness = std::clamp<std::int64_t>(settings.slab_samples / std::max<std::int64_t>(m.plane, 1), 1, m.ni);
  NullProgress silent;
  m.first_pass(std::move(keys), progress ? *progress : silent, cancel);
}

LabelCube::~LabelCube() = default;

const volume::Geometry& LabelCube::geometry() const {
  return impl_->field->geometry();
}

std::string LabelCube::source() const {
  return "body labels of " + impl_->field->source();
}

const std::vector<LabelledBody>& LabelCube::bodies() const {
  return impl_->bodies;
}

std::uint64_t LabelCube::provisional_labels() const {
  return impl_->final_id.size();
}

void LabelCube::read_box(const Box& box, std::span<float> out) const {
  Impl& m = *impl_;
  if (box.lo[0] < m.window_lo || box.hi[0] > m.window_hi) {
    const std::int64_t s0 = box.lo[0] / m.thickness, s1 = (box.hi[0] - 1) / m.thickness;
    m.window_lo = s0 * m.thickness;
    m.window_hi = std::min(m.ni, (s1 + 1) * m.thickness);
    m.window.resize(static_cast<std::size_t>((m.window_hi - m.window_lo) * m.plane));
    for (std::int64_t s = s0; s <= s1; ++s) {
      m.label_of(s);
      const std::uint64_t offset = m.slab_offset[static_cast<std::size_t>(s)];
      std::uint32_t* to = m.window.data() + (s - s0) * m.thickness * m.plane;
      for (std::size_t n = 0; n < m.label.size(); ++n)
        to[n] = m.label[n] < 0 ? 0u : m.final_id[offset + static_cast<std::uint64_t>(m.label[n])];
    }
  }
  std::size_t o = 0;
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j) {
      const std::uint32_t* row = m.window.data() + ((i - m.window_lo) * m.nj + j) * m.nk;
      for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
        out[o++] = static_cast<float>(row[k]);
    }
}

namespace {

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void remove_quietly(const fs::path& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

} // namespace

LabelLike label_like_of_input(const nlohmann::json& in) {
  LabelLike like;
  if (!in.is_object() || !in.contains("file")) return like;
  like.file = in.at("file").get<std::string>();
  like.options.nan_policy = volume::parse_nan_policy(in.value("nan", "error"));
  if (in.contains("segy")) like.options.segy = volume::segy_options_from_json(in["segy"]);
  return like;
}

std::vector<std::string> label_extensions(const LabelLike& like) {
  if (like.file.empty()) return {};
  const std::string format = volume::detect_format(like.file);
  if (format == "SEG-Y") return {".segy", ".sgy"};
  if (format == "netCDF-4" || format == "HDF5") return {".nc"};
  if (format == "Zarr") return {".zarr"};
  if (format == "raw") return {".raw"};
  return {".tif"}; // GeoTIFF, ENVI: the classic raster family
}

void check_label_format(const LabelLike& like, const std::string& path) {
  volume::check_output_format(path);
  const std::vector<std::string> family = label_extensions(like);
  const std::string ext = lower_extension(path);
  if (family.empty() || std::find(family.begin(), family.end(), ext) != family.end()) return;
  throw InvalidArgument("the label cube is written in the input's format family (" + volume::detect_format(like.file) +
                            "), but '" + path + "' names another",
                        {like.file}, "name it " + fs::path(path).replace_extension(family.front()).string());
}

LabelOutput write_label_cube(std::shared_ptr<const volume::Volume> field, const LabelSettings& settings,
                             const std::vector<std::uint64_t>& keys, const LabelLike& like, const std::string& path,
                             bool overwrite, const nlohmann::json& description, const std::string& note,
                             Progress* progress, const CancelToken& cancel) {
  using Clock = std::chrono::steady_clock;
  check_label_format(like, path);
  const bool segy_like = !like.file.empty() && volume::detect_format(like.file) == "SEG-Y";
  const fs::path target = fs::absolute(path).lexically_normal();
  const std::string ext = lower_extension(target);
  const fs::path csv = target.string() + ".bodies.csv", json = target.string() + ".bodies.json";
  std::error_code ec;
  for (const fs::path& p : {target, csv, json})
    if (fs::exists(fs::symlink_status(p, ec))) {
      if (!overwrite) throw IoError("the output already exists", {p.string()}, "remove it or pass --overwrite");
      require_replaceable(p, p == target && ext == ".zarr");
    }
  if (!fs::is_directory(target.parent_path(), ec))
    throw IoError("the label cube's directory does not exist", {target.parent_path().string()}, "create it first");

  LabelOutput result;
  const auto t0 = Clock::now();
  auto cube = std::make_shared<LabelCube>(std::move(field), settings, keys, progress, cancel);
  const auto t1 = Clock::now();
  result.seconds_label = std::chrono::duration<double>(t1 - t0).count();

  // Whole or not at all: written under a name of this process beside the target, then renamed.
  static std::atomic<unsigned> serial{0};
  const fs::path temporary = target.parent_path() / ("." + target.stem().string() + ".labels-" +
                                                     std::to_string(::getpid()) + "-" + std::to_string(serial++) + ext);
  const bool raw = ext == ".raw";
  try {
    volume::WriteOptions w;
    w.variable = "body_id";
    w.note = note;
    if (segy_like)
      volume::write_segy_like(*cube, like.file, like.options, temporary.string(), w, progress, cancel);
    else
      volume::write_volume(*cube, temporary.string(), w, progress, cancel);
    if (fs::exists(fs::symlink_status(target, ec))) remove_quietly(target);
    if (raw) {
      fs::rename(temporary.string() + ".json", target.string() + ".json");
    }
    fs::rename(temporary, target);
  } catch (const fs::filesystem_error& e) {
    remove_quietly(temporary);
    if (raw) remove_quietly(temporary.string() + ".json");
    throw IoError(std::string("cannot put the label cube in place: ") + e.code().message(), {target.string()});
  } catch (...) {
    remove_quietly(temporary);
    if (raw) remove_quietly(temporary.string() + ".json");
    throw;
  }
  result.seconds_write = std::chrono::duration<double>(Clock::now() - t1).count();
  result.bodies = cube->bodies();

  std::ostringstream table;
  table << "id,key,samples,keys\n";
  nlohmann::json doc = description.is_object() ? description : nlohmann::json::object();
  doc["cube"] = target.filename().string();
  doc["iso"] = settings.iso;
  doc["side"] = settings.below ? "below" : "above";
  doc["outside"] = 0;
  doc["connectivity"] = "6 (face neighbours), as marching cubes' inside";
  doc["bodies"] = nlohmann::json::array();
  for (const auto& b : result.bodies) {
    table << b.id << ',' << b.key << ',' << b.samples << ',';
    for (std::size_t n = 0; n < b.keys.size(); ++n)
      table << (n ? ";" : "") << b.keys[n];
    table << '\n';
    doc["bodies"].push_back({{"id", b.id}, {"key", b.key}, {"samples", b.samples}, {"keys", b.keys}});
  }
  write_file_atomically(csv, table.str(), "the label table");
  write_file_atomically(json, doc.dump(2) + "\n", "the label table");
  result.cube = target.string();
  result.table = csv.string();
  result.json = json.string();
  return result;
}

} // namespace geotandem::workflow
