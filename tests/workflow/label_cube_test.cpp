// The label cube (issue 54, part 3) against an independent voxel labelling (flood fill of the
// 6-connected samples on the same side of iso, tests/support/voxel_components.hpp), for every kept
// body of an analytic and a synthetic seismic cube, on both sides of iso; the side below against
// the extraction of the negated cube; the files in every format read back.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/component_steps.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/label_cube.hpp"
#include "scratch.hpp"
#include "voxel_components.hpp"

namespace {

using namespace geotandem;
using namespace geotandem::workflow;
using volume::Box;

struct Case {
  const char* name;
  bool seismic;
  bool below;
};

std::shared_ptr<const volume::MemoryVolume> cube_of(bool seismic) {
  std::unique_ptr<synth::SyntheticCube> cube;
  if (seismic) {
    synth::SeismicOptions o;
    o.shape = {44, 40, 48};
    o.seed = 2;
    cube = synth::make_seismic(o);
  } else {
    synth::AnalyticOptions o;
    o.shape = {44, 42, 40};
    o.seed = 3;
    cube = synth::make_analytic(o);
  }
  return volume::MemoryVolume::copy_of(*cube);
}

// An isovalue with some hundred bodies: a high quantile above, a low one below (analytic: the
// background below 0.3 is one body around the planted ones, which are its cavities).
float iso_of(const std::vector<float>& values, bool seismic, bool below) {
  if (!seismic) return below ? 0.3f : 0.5f;
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const double q = below ? 0.04 : 0.96;
  return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size()))];
}

std::vector<std::uint64_t> keys_of(const store::ComponentStore& store) {
  std::vector<std::uint64_t> keys;
  for (const auto& row : store.query())
    keys.push_back(row.key);
  return keys;
}

store::ComponentStore extract(const volume::Volume& cube, float iso, bool below, const std::string& dir,
                              std::int64_t block_size = 16) {
  auto store = store::ComponentStore::create(dir, cube.geometry());
  ExtractionOptions o;
  o.iso = iso;
  o.side = below ? tandem::Side::below : tandem::Side::above;
  o.block_size = block_size;
  NullProgress progress;
  std::ostringstream text;
  Logger log{text, LogLevel::warning};
  extract_to_store(cube, store, o, ExecutionContext{}, log, progress, CancelToken{});
  return store;
}

class LabelCubes : public ::testing::TestWithParam<Case> {};

TEST_P(LabelCubes, EveryKeptBodyIsExactlyItsVoxelComponent) {
  const Case c = GetParam();
  auto cube = cube_of(c.seismic);
  const auto& shape = cube->geometry().shape;
  const std::vector<float>& values = cube->samples();
  const float iso = iso_of(values, c.seismic, c.below);
  geotandem::testing::ScratchDir dir;
  auto store = extract(*cube, iso, c.below, dir.file("store"));
  const std::vector<std::uint64_t> all = keys_of(store);
  ASSERT_GT(all.size(), 5u);
  // A selection, as bubble removal leaves one: two keys in three.
  std::vector<std::uint64_t> kept;
  for (std::size_t n = 0; n < all.size(); ++n)
    if (n % 3 != 1) kept.push_back(all[n]);

  // The oracle: flood fill of the samples on the same side (the side below: the negated cube at
  // the negated iso, which is how marching cubes decides it, ties inside).
  std::vector<float> side(values);
  if (c.below)
    for (float& v : side)
      v = -v;
  std::vector<std::int32_t> component;
  const auto components = geotandem::testing::voxel_components(side, shape, c.below ? -iso : iso, &component);
  // A key's component: the inside end of its crossed lattice edge (exactly one end is inside).
  const std::int64_t plane = shape[1] * shape[2], stride[3] = {plane, shape[2], 1};
  const auto samples = static_cast<std::uint64_t>(shape[0] * plane);
  std::map<std::int32_t, std::uint64_t> smallest_key; // oracle component -> its smallest kept key
  for (std::uint64_t key : kept) {
    std::vector<std::uint64_t> ends;
    if (key / 3 >= samples)
      ends = {key - 3 * samples};
    else
      ends = {key / 3, key / 3 + static_cast<std::uint64_t>(stride[key % 3])};
    std::int32_t inside = -1;
    int count = 0;
    for (std::uint64_t e : ends)
      if (component[e] >= 0) {
        inside = component[e];
        ++count;
      }
    ASSERT_EQ(count, 1) << "key " << key;
    auto [it, fresh] = smallest_key.emplace(inside, key);
    if (!fresh) it->second = std::min(it->second, key);
  }
  std::vector<std::uint64_t> body_keys;
  for (const auto& [comp, key] : smallest_key)
    body_keys.push_back(key);
  std::sort(body_keys.begin(), body_keys.end());
  std::map<std::int32_t, float> id_of;
  for (const auto& [comp, key] : smallest_key)
    id_of[comp] = static_cast<float>(std::lower_bound(body_keys.begin(), body_keys.end(), key) - body_keys.begin() + 1);
  std::vector<float> expected(values.size(), 0.0f);
  for (std::size_t n = 0; n < values.size(); ++n)
    if (component[n] >= 0)
      if (auto it = id_of.find(component[n]); it != id_of.end()) expected[n] = it->second;

  LabelSettings settings;
  settings.iso = iso;
  settings.below = c.below;
  settings.slab_samples = 5 * plane; // slabs of 5 inlines: bodies cross slab and block boundaries
  LabelCube labels(cube, settings, kept);
  ASSERT_EQ(labels.bodies().size(), body_keys.size());
  const std::vector<float> got = labels.read(Box::of_shape(shape));
  std::size_t wrong = 0;
  for (std::size_t n = 0; n < got.size(); ++n)
    wrong += got[n] != expected[n];
  EXPECT_EQ(wrong, 0u) << "of " << got.size() << " samples";
  for (const auto& body : labels.bodies()) {
    EXPECT_EQ(body.key, body_keys[body.id - 1]);
    EXPECT_EQ(body.key, body.keys.front());
    std::int32_t comp = -1;
    for (const auto& [k, id] : id_of)
      if (id == static_cast<float>(body.id)) comp = k;
    ASSERT_GE(comp, 0);
    EXPECT_EQ(body.samples, components[static_cast<std::size_t>(comp)].voxels) << "body " << body.id;
  }

  // Volumes in samples (issue 54, part 6): every surface of a voxel component counts the samples
  // it encloses (a cavity's negative), so those of one component sum to its voxels exactly.
  std::map<std::int32_t, std::int64_t> counted;
  for (const auto& row : store.query()) {
    ASSERT_TRUE(row.samples_counted);
    const std::uint64_t key = row.key;
    const std::uint64_t end = key / 3 >= samples ? key - 3 * samples : key / 3;
    const std::uint64_t other = key / 3 >= samples ? end : end + static_cast<std::uint64_t>(stride[key % 3]);
    const std::int32_t comp = component[end] >= 0 ? component[end] : component[other];
    ASSERT_GE(comp, 0);
    counted[comp] += row.stats.samples;
    // Signed alike: a body's surface encloses a positive volume, a cavity's a negative one (up to
    // bodies of a voxel or two, which the simplification may flatten to nearly nothing).
    const double voxel = 25.0 * 25.0 * 4.0;
    if (row.stats.samples > 0) {
      EXPECT_GT(row.stats.volume, -1e-6 * voxel) << "key " << key;
    } else {
      EXPECT_LT(row.stats.volume, 1e-6 * voxel) << "key " << key;
    }
  }
  std::size_t bodies_with_surfaces = 0;
  for (const auto& [comp, n] : counted) {
    EXPECT_EQ(n, static_cast<std::int64_t>(components[static_cast<std::size_t>(comp)].voxels)) << "component " << comp;
    ++bodies_with_surfaces;
  }
  EXPECT_EQ(bodies_with_surfaces, components.size()) << "every voxel component has a surface in the store";

  // The slabs change nothing: one inline at a time, or the whole cube at once.
  for (std::int64_t budget : {std::int64_t{1}, std::int64_t{1} << 30}) {
    settings.slab_samples = budget;
    LabelCube other(cube, settings, kept);
    EXPECT_EQ(other.read(Box::of_shape(shape)), got) << "slab budget " << budget;
  }
  // Reads of any box, in any order, are the whole cube's.
  for (const Box& box : {Box{{30, 3, 7}, {37, 20, 30}}, Box{{0, 0, 0}, {9, 40, 1}}, Box{{12, 5, 2}, {40, 9, 5}}}) {
    const Box inside = box.intersection(Box::of_shape(shape));
    const std::vector<float> part = labels.read(inside);
    std::size_t o = 0, bad = 0;
    for (std::int64_t i = inside.lo[0]; i < inside.hi[0]; ++i)
      for (std::int64_t j = inside.lo[1]; j < inside.hi[1]; ++j)
        for (std::int64_t k = inside.lo[2]; k < inside.hi[2]; ++k)
          bad += part[o++] != got[static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k)];
    EXPECT_EQ(bad, 0u) << inside.to_string();
  }
}

INSTANTIATE_TEST_SUITE_P(Sides, LabelCubes,
                         ::testing::Values(Case{"AnalyticAbove", false, false}, Case{"AnalyticBelow", false, true},
                                           Case{"SeismicAbove", true, false}, Case{"SeismicBelow", true, true}),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// The side below is the negated cube's side above: the same keys, meshes and measures, with normals
// out of the bodies (positive volumes).
TEST(LabelSides, BelowIsTheNegatedCubeAbove) {
  for (bool seismic : {false, true}) {
    auto cube = cube_of(seismic);
    const float iso = iso_of(cube->samples(), seismic, true);
    std::vector<float> negated(cube->samples());
    for (float& v : negated)
      v = -v;
    volume::MemoryVolume flipped(cube->geometry(), negated);
    geotandem::testing::ScratchDir dir;
    auto below = extract(*cube, iso, true, dir.file("below"));
    auto above = extract(flipped, -iso, false, dir.file("above"));
    const auto a = below.query(), b = above.query();
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 3u);
    double total = 0;
    for (std::size_t n = 0; n < a.size(); ++n) {
      EXPECT_EQ(a[n].key, b[n].key);
      EXPECT_EQ(a[n].stats.triangle_count, b[n].stats.triangle_count);
      EXPECT_EQ(a[n].stats.volume, b[n].stats.volume);
      EXPECT_EQ(a[n].stats.centroid, b[n].stats.centroid);
      total += a[n].stats.volume;
    }
    EXPECT_GT(total, 0.0) << "normals point out of the bodies";
    // And the side below is not the side above at the same iso: together they count every sample
    // once, and the samples equal to iso twice (volumes in samples sum to the inside samples).
    auto other = extract(*cube, iso, false, dir.file("other"));
    std::int64_t counted = 0, ties = 0;
    for (const auto& row : other.query())
      counted += row.stats.samples;
    for (const auto& row : below.query())
      counted += row.stats.samples;
    for (float v : cube->samples())
      ties += v == iso;
    EXPECT_EQ(counted, static_cast<std::int64_t>(cube->samples().size()) + ties);
  }
}

// min_samples drops exactly the components enclosing fewer samples, whatever their volume unit.
TEST(LabelSamples, MinSamplesDropsExactlyTheSmallerBodies) {
  auto cube = cube_of(false);
  geotandem::testing::ScratchDir dir;
  auto store = extract(*cube, 0.5f, false, dir.file("store"));
  const auto rows = store.query();
  std::vector<std::int64_t> counts;
  for (const auto& r : rows)
    counts.push_back(r.stats.samples);
  std::sort(counts.begin(), counts.end());
  ASSERT_GT(counts.back(), 2);
  const std::int64_t threshold = counts.back() / 2 + 1; // the largest kept, the smallest dropped
  BubbleRemoval rules;
  rules.min_samples = threshold;
  const BubbleResult result = remove_bubbles(store, rules);
  std::vector<std::uint64_t> expected;
  for (const auto& r : rows)
    if (r.stats.samples >= threshold) expected.push_back(r.key);
  std::vector<std::uint64_t> kept = result.kept;
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, expected);
  EXPECT_LT(kept.size(), rows.size());
  EXPECT_GT(kept.size(), 0u);
}

TEST(LabelFiles, EveryFormatReadsBackAsTheLabels) {
  auto cube = cube_of(true);
  const float iso = iso_of(cube->samples(), true, false);
  geotandem::testing::ScratchDir dir;
  auto store = extract(*cube, iso, false, dir.file("store"), 0);
  const auto keys = keys_of(store);
  LabelSettings settings;
  settings.iso = iso;
  const std::vector<float> expected = LabelCube(cube, settings, keys).read(Box::of_shape(cube->geometry().shape));
  for (const char* name : {"labels.raw", "labels.nc", "labels.segy", "labels.zarr"}) {
    const std::string path = dir.file(name);
    const auto out =
        write_label_cube(cube, settings, keys, {}, path, false, {{"store", "store"}}, "body labels", nullptr, {});
    auto back = volume::open_volume(path);
    EXPECT_EQ(back->geometry().shape, cube->geometry().shape) << name;
    EXPECT_EQ(back->read(Box::of_shape(cube->geometry().shape)), expected) << name;
    std::ifstream csv(out.table);
    std::string line;
    std::size_t rows = 0;
    std::getline(csv, line);
    EXPECT_EQ(line, "id,key,samples,keys");
    while (std::getline(csv, line))
      ++rows;
    EXPECT_EQ(rows, out.bodies.size());
    // No temporary left beside it; a second write is refused without overwrite, done with it.
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      EXPECT_EQ(entry.path().filename().string().find(".labels-"), std::string::npos) << entry.path();
    EXPECT_THROW(write_label_cube(cube, settings, keys, {}, path, false, {}, "", nullptr, {}), IoError);
    EXPECT_NO_THROW(write_label_cube(cube, settings, keys, {}, path, true, {}, "", nullptr, {}));
  }
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::int32_t big_endian_int32(const char* p) {
  std::uint32_t v = 0;
  for (int n = 0; n < 4; ++n)
    v = (v << 8) | static_cast<unsigned char>(p[n]);
  return static_cast<std::int32_t>(v);
}

float big_endian_float(const char* p) {
  const auto bits = static_cast<std::uint32_t>(big_endian_int32(p));
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// A SEG-Y input gives a SEG-Y label cube that is its file trace for trace: the same textual header
// but for the note's card, the same binary header (IEEE floats both), every trace header byte for
// byte in the file's own order (here a shuffled, unsorted file read through its trace index), and
// each trace's samples the labels of its bin. Another family's extension is refused.
TEST(LabelFiles, SegyLabelsKeepTheInputsHeadersTraceForTrace) {
  auto cube = cube_of(true);
  const auto& shape = cube->geometry().shape;
  geotandem::testing::ScratchDir dir;
  const std::string sorted = dir.file("sorted.segy"), input = dir.file("input.segy");
  volume::write_volume(*cube, sorted);
  // Shuffle the traces (a fixed permutation): the reader needs its trace index for this file.
  std::string bytes = file_bytes(sorted);
  const std::size_t trace_bytes = 240 + 4 * static_cast<std::size_t>(shape[2]);
  const std::size_t traces = static_cast<std::size_t>(shape[0] * shape[1]);
  ASSERT_EQ(bytes.size(), 3600 + traces * trace_bytes);
  std::string shuffled = bytes.substr(0, 3600);
  for (std::size_t t = 0; t < traces; ++t) {
    const std::size_t from = (t * 7919) % traces; // 7919 is prime, coprime with the trace count
    shuffled += bytes.substr(3600 + from * trace_bytes, trace_bytes);
  }
  put_bytes(input, shuffled);
  auto in = std::shared_ptr<const volume::Volume>(volume::open_volume(input));
  ASSERT_EQ(in->geometry().shape, shape);
  bool unsorted = false;
  for (const auto& d : in->format_details())
    if (d.key == "sorting") unsorted = d.value.find("unsorted") != std::string::npos;
  ASSERT_TRUE(unsorted) << "the file must be read through its trace index";

  const float iso = iso_of(cube->samples(), true, false);
  auto store = extract(*in, iso, false, dir.file("store"));
  const auto keys = keys_of(store);
  LabelSettings settings;
  settings.iso = iso;
  const std::vector<float> labels = LabelCube(in, settings, keys).read(Box::of_shape(shape));
  LabelLike like;
  like.file = input;
  EXPECT_THROW(write_label_cube(in, settings, keys, like, dir.file("labels.nc"), false, {}, "", nullptr, {}),
               InvalidArgument);
  const std::string path = dir.file("labels.sgy");
  write_label_cube(in, settings, keys, like, path, false, {}, "geotandem body labels", nullptr, {});

  const std::string out = file_bytes(path);
  ASSERT_EQ(out.size(), shuffled.size());
  std::size_t cards_changed = 0;
  for (std::size_t card = 0; card < 40; ++card)
    cards_changed += out.compare(card * 80, 80, shuffled, card * 80, 80) != 0;
  EXPECT_EQ(cards_changed, 1u) << "one card holds the note";
  EXPECT_EQ(out.compare(3200, 400, shuffled, 3200, 400), 0) << "the binary header";
  std::size_t headers_differ = 0, samples_differ = 0;
  for (std::size_t t = 0; t < traces; ++t) {
    const std::size_t at = 3600 + t * trace_bytes;
    headers_differ += out.compare(at, 240, shuffled, at, 240) != 0;
    const std::int64_t i = big_endian_int32(out.data() + at + 188) - static_cast<std::int64_t>(in->geometry().inline0);
    const std::int64_t j =
        big_endian_int32(out.data() + at + 192) - static_cast<std::int64_t>(in->geometry().crossline0);
    ASSERT_TRUE(i >= 0 && i < shape[0] && j >= 0 && j < shape[1]) << "trace " << t;
    for (std::int64_t k = 0; k < shape[2]; ++k)
      samples_differ += big_endian_float(out.data() + at + 240 + 4 * static_cast<std::size_t>(k)) !=
                        labels[static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k)];
  }
  EXPECT_EQ(headers_differ, 0u);
  EXPECT_EQ(samples_differ, 0u);
  // And geotandem reads it back as the labels, on the input's grid.
  auto back = volume::open_volume(path);
  EXPECT_EQ(back->geometry(), in->geometry());
  EXPECT_EQ(back->read(Box::of_shape(shape)), labels);
}

TEST(LabelFiles, KeysOfAnotherCubeAreRefused) {
  auto cube = cube_of(false);
  geotandem::testing::ScratchDir dir;
  auto store = extract(*cube, 0.5f, false, dir.file("store"));
  LabelSettings settings;
  settings.iso = 0.5f;
  auto keys = keys_of(store);
  EXPECT_NO_THROW((LabelCube{cube, settings, keys}));
  settings.below = true; // the other side: the keys' edges are crossed, but seed the other side
  settings.iso = 0.95f;
  EXPECT_THROW((LabelCube{cube, settings, keys}), DataError);
  settings = LabelSettings{};
  settings.iso = 0.5f;
  // An edge along k between two outside samples is not crossed: no surface has that key.
  const auto& v = cube->samples();
  std::uint64_t outside = 0;
  while (!(v[outside] < 0.5f && v[outside + 1] < 0.5f && (outside + 1) % 40 != 0))
    ++outside;
  EXPECT_THROW((LabelCube{cube, settings, {3 * outside + 2}}), DataError);
}

} // namespace
