// Irregular SEG-Y surveys (sorted traces leaving bins of their rectangle empty) and surveys padded
// with placeholders: what is refused and how, what is read, and the grid handed to other processes.

#include <gtest/gtest.h>

#include <cstring>
#include <segyio/segy.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"
#include "segy_fixtures.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using namespace geotandem::volume::testing; // the cube and SEG-Y fixtures

namespace {

// A whole inline missing (numbers 100, 102, 104, 108, ...): named by the jump in the numbers; with
// the fill policy the cube has the missing inline, all of it missing samples.
TEST(SegyIrregular, AMissingLineIsNamedByTheJumpInItsNumbers) {
  ScratchDir dir;
  SegySpec s;
  s.gap_in_inlines = true;
  const std::string path = dir.file("gap.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("no trace on inline 106: the inline numbers go 104 then 108 where the step is 2"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  const auto cube =
      open_volume(path, {.nan_policy = NanPolicy::fill, .fill_value = std::numeric_limits<float>::quiet_NaN()});
  ASSERT_EQ(cube->geometry().shape, (Index3{8, 9, 50}));
  const auto samples = cube->read(cube->geometry().bounds());
  const Box all = cube->geometry().bounds();
  for (std::int64_t i = 0; i < 8; ++i)
    for (std::int64_t j = 0; j < 9; ++j) {
      const float v = samples[all.offset({i, j, 7})];
      // Inline index 3 (number 106) is the missing one; index i >= 4 holds the file's inline i - 1.
      if (i == 3)
        EXPECT_TRUE(std::isnan(v)) << i << ", " << j;
      else
        EXPECT_EQ(v, formula(i < 3 ? i : i - 1, j, 7)) << i << ", " << j;
    }
}

// An irregular survey (sorted traces, some bins of the line-number rectangle without one, here a
// corner and an inner trace): refused by default, naming the missing trace and the way out; with
// the fill policy read as the full survey with missing samples where the traces are missing. The
// oracle is the same survey written with every trace, read by the regular path.
TEST(SegyIrregular, MissingTracesAreMissingSamples) {
  ScratchDir dir;
  for (bool crossline_sorted : {false, true}) {
    SegySpec s;
    s.crossline_sorted = crossline_sorted;
    const std::string full_path = dir.file(crossline_sorted ? "xl_full.sgy" : "il_full.sgy");
    write_with_segyio(full_path, s);
    s.missing = {{0, 0}, {3, 4}};
    const std::string path = dir.file(crossline_sorted ? "xl.sgy" : "il.sgy");
    write_with_segyio(path, s);
    const std::string message = message_of<FormatError>([&] { open_volume(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("irregular survey at bytes 189/193: 61 of 63 traces (7 inlines x 9 crosslines)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("the first missing: inline 100, crossline 300"), std::string::npos) << message;
    EXPECT_NE(message.find("--nan fill"), std::string::npos) << message;
    EXPECT_NE(message.find("pad"), std::string::npos) << message;

    const auto full = open_volume(full_path);
    const auto irregular =
        open_volume(path, {.nan_policy = NanPolicy::fill, .fill_value = std::numeric_limits<float>::quiet_NaN()});
    const Geometry& g = irregular->geometry();
    expect_same_grid(g, full->geometry());
    // The affine fitted to every trace present (the corner (0, 0) is missing) against the one from
    // the full file's corners: the same within the coordinates' rounding (scalar -100: 0.01 m).
    expect_near_at_corners(g.affine, full->geometry().affine, g.shape, 0.02);
    for (const Box& box : probe_boxes(g.shape)) {
      const auto got = irregular->read(box);
      const auto expected = full->read(box);
      for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
        for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
          for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k) {
            const bool missing = (i == 0 && j == 0) || (i == 3 && j == 4);
            const float v = got[box.offset({i, j, k})];
            if (missing)
              ASSERT_TRUE(std::isnan(v)) << "(" << i << ", " << j << ", " << k << ") of box " << box.to_string();
            else
              ASSERT_EQ(v, expected[box.offset({i, j, k})])
                  << "(" << i << ", " << j << ", " << k << ") of box " << box.to_string();
          }
    }
    bool said = false;
    for (const auto& d : irregular->format_details())
      if (d.key == "traces") {
        said = true;
        EXPECT_NE(d.value.find("61 of 63 traces"), std::string::npos) << d.value;
      }
    EXPECT_TRUE(said);
  }
}

// Placeholders: traces flagged dead whose headers are zero but for the sample count and interval,
// as some programs pad a survey to its full rectangle. Where they pad it (here the first, an inner
// and the last trace), each is a dead trace in its place: the file opens without the NaN policy,
// with the sample axis and affine of the same survey written whole (not the zeros of trace 0),
// and reads as that survey with zeros at the placeholders. That holds whether the grid is found
// from the corners (an inner placeholder only) or by reading every header. Placeholders after
// the survey's traces are left out, and the survey is read whole. Beside a missing trace, the
// placeholders' bins cannot be known: they are left out, and the message says so.
// What a Progress was told.
class RecordingProgress final : public Progress {
public:
  std::vector<std::string> begun;
  std::uint64_t total = 0, last = 0;
  int ended = 0, stopped = 0;
  void begin(const std::string& label, std::uint64_t count, const std::string& unit) override {
    begun.push_back(label + " (" + unit + ")");
    total = count;
    last = 0;
  }
  void update(std::uint64_t done) override {
    EXPECT_GE(done, last) << "progress went back";
    last = done;
  }
  void end() override { ++ended; }
  void stop() override { ++stopped; }
};

// The pass over every trace header that an irregular survey needs reports its progress, to the
// last trace; a regular survey, whose grid comes from a few headers, reports nothing.
TEST(SegyIrregular, ThePassOverEveryTraceHeaderReportsItsProgress) {
  ScratchDir dir;
  SegySpec s;
  const std::string full_path = dir.file("full.sgy");
  write_with_segyio(full_path, s);
  s.missing = {{0, 0}, {3, 4}};
  const std::string path = dir.file("irregular.sgy");
  write_with_segyio(path, s);

  RecordingProgress regular;
  OpenOptions options{.nan_policy = NanPolicy::fill, .fill_value = std::numeric_limits<float>::quiet_NaN()};
  options.progress = &regular;
  open_volume(full_path, options);
  EXPECT_TRUE(regular.begun.empty());

  RecordingProgress scan;
  options.progress = &scan;
  const auto cube = open_volume(path, options);
  ASSERT_EQ(scan.begun, std::vector<std::string>{"reading trace headers (traces)"});
  EXPECT_EQ(scan.total, 61u);
  EXPECT_EQ(scan.last, 61u);
  EXPECT_EQ(scan.ended, 1);
  EXPECT_EQ(scan.stopped, 0);
  EXPECT_EQ(cube->geometry().shape, (Index3{7, 9, s.ns}));

  // Refused after the pass (missing traces under the default policy): the task is stopped, not
  // left running.
  RecordingProgress refused;
  OpenOptions strict;
  strict.progress = &refused;
  message_of<FormatError>([&] { open_volume(path, strict); });
  EXPECT_EQ(refused.begun.size(), 1u);
  EXPECT_EQ(refused.ended + refused.stopped, 1);
}

TEST(SegyIrregular, PlaceholdersPaddingASurveyAreDeadTracesInTheirPlaces) {
  ScratchDir dir;
  for (bool crossline_sorted : {false, true}) {
    SCOPED_TRACE(crossline_sorted ? "crossline-sorted" : "inline-sorted");
    SegySpec s;
    s.crossline_sorted = crossline_sorted;
    s.delay_ms = 100;
    const std::string name = crossline_sorted ? "xl" : "il";
    const std::string full_path = dir.file(name + "_full.sgy");
    write_with_segyio(full_path, s);
    const auto full = open_volume(full_path);
    using Places = std::vector<std::array<int, 2>>;
    for (const Places& places : {Places{{0, 0}, {3, 4}, {6, 8}}, Places{{3, 4}}}) {
      SCOPED_TRACE(places.size());
      s.placeholders = places;
      const std::string path = dir.file(name + std::to_string(places.size()) + ".sgy");
      write_with_segyio(path, s);
      const auto padded = open_volume(path);
      // A placeholder in a corner takes the pass over every header, which the workers are spared.
      const std::string hint = padded->reopen_hint();
      EXPECT_EQ(hint.empty(), places.size() == 1) << hint;
      if (!hint.empty()) {
        OpenOptions hinted;
        hinted.reopen_hint = hint;
        EXPECT_EQ(open_volume(path, hinted)->geometry(), padded->geometry());
      }
      const Geometry &g = padded->geometry(), &want = full->geometry();
      expect_same_grid(g, want);
      EXPECT_EQ(g.z0, 100.0);
      expect_near_at_corners(g.affine, want.affine, g.shape, 0.02);
      const Box all = want.bounds();
      const auto got = padded->read(all), expected = full->read(all);
      for (std::int64_t i = 0; i < all.hi[0]; ++i)
        for (std::int64_t j = 0; j < all.hi[1]; ++j) {
          const bool placeholder =
              std::find(places.begin(), places.end(), std::array<int, 2>{int(i), int(j)}) != places.end();
          for (std::int64_t k = 0; k < all.hi[2]; ++k)
            ASSERT_EQ(got[all.offset({i, j, k})], placeholder ? 0.0f : expected[all.offset({i, j, k})])
                << "(" << i << ", " << j << ", " << k << ")";
        }
    }
    // Placeholders after the survey: every bin has its trace, so nothing is missing.
    s.placeholders = {};
    s.trailing_placeholders = 2;
    const std::string trailing_path = dir.file(name + "_trailing.sgy");
    write_with_segyio(trailing_path, s);
    const auto trailing = open_volume(trailing_path);
    EXPECT_EQ(trailing->geometry().shape, full->geometry().shape);
    EXPECT_EQ(trailing->geometry().z0, 100.0);
    EXPECT_EQ(trailing->read(full->geometry().bounds()), full->read(full->geometry().bounds()));
    for (const auto& d : trailing->format_details()) {
      if (d.key != "traces") continue;
      EXPECT_EQ(d.value, "63, every bin of the grid; 2 placeholders (dead traces with line numbers 0) besides them, "
                         "not read");
    }
    OpenOptions hinted;
    hinted.reopen_hint = trailing->reopen_hint();
    ASSERT_FALSE(hinted.reopen_hint.empty());
    EXPECT_EQ(open_volume(trailing_path, hinted)->format_details(), trailing->format_details());
    s.trailing_placeholders = 0;

    s.placeholders = {{0, 0}};
    s.missing = {{3, 4}};
    const std::string path = dir.file(name + "_holes.sgy");
    write_with_segyio(path, s);
    const std::string message = message_of<FormatError>([&] { open_volume(path); });
    EXPECT_NE(message.find("61 of 63 traces (7 inlines x 9 crosslines; 1 placeholders, dead traces with line "
                           "numbers 0, left out"),
              std::string::npos)
        << message;
    const auto irregular =
        open_volume(path, {.nan_policy = NanPolicy::fill, .fill_value = std::numeric_limits<float>::quiet_NaN()});
    EXPECT_EQ(irregular->geometry().z0, 100.0);
    const auto got = irregular->read(full->geometry().bounds());
    EXPECT_TRUE(std::isnan(got[full->geometry().bounds().offset({0, 0, 5})]));
    EXPECT_TRUE(std::isnan(got[full->geometry().bounds().offset({3, 4, 5})]));
    EXPECT_EQ(got[full->geometry().bounds().offset({0, 1, 5})], formula(0, 1, 5));
  }
}

// An irregular survey's grid takes a pass over every trace header. The volume hands it on
// (reopen_hint), so that another process opening the file with it (a worker) skips that pass while
// the file keeps its size and modification time. Shown by changing one trace's coordinates and
// setting the time back: the hint gives the affine found before, a plain open the new one. Once
// the time differs, and for a hint that is garbage, for other header bytes or that does not place
// every trace, the file is read as without a hint. A full grid needs no hint, nor does a survey
// with holes everywhere (its hint would weigh about as much as the headers).
TEST(SegyIrregular, AnIrregularGridIsHandedOnAndUsedWhileTheFileIsUnchanged) {
  ScratchDir dir;
  for (int variant = 0; variant < 3; ++variant) { // inline-sorted, crossline-sorted, inline numbers counting down
    SCOPED_TRACE(variant);
    SegySpec s;
    s.crossline_sorted = variant == 1;
    if (variant == 2) {
      s.il0 = 112;
      s.il_step = -2;
    }
    const std::string name = std::to_string(variant);
    const std::string full_path = dir.file(name + "_full.sgy");
    write_with_segyio(full_path, s);
    EXPECT_EQ(open_volume(full_path)->reopen_hint(), "");
    s.missing = {{0, 0}, {3, 4}, {6, 2}};
    const std::string path = dir.file(name + ".sgy");
    write_with_segyio(path, s);
    const OpenOptions fill{.nan_policy = NanPolicy::fill, .fill_value = std::numeric_limits<float>::quiet_NaN()};
    const auto first = open_volume(path, fill);
    const std::string hint = first->reopen_hint();
    ASSERT_FALSE(hint.empty());
    // About a run per line, not one per trace (7 x 9 traces, 60 in the file).
    const auto runs = std::count(hint.begin(), hint.end(), '[') - 4; // the other arrays: bytes, lines, affine, runs
    EXPECT_LE(runs, 16) << hint;

    OpenOptions hinted = fill;
    hinted.reopen_hint = hint;
    const auto again = open_volume(path, hinted);
    EXPECT_EQ(again->geometry(), first->geometry());
    EXPECT_EQ(again->format_details(), first->format_details());
    EXPECT_EQ(again->reopen_hint(), hint);
    const Box all = first->geometry().bounds();
    const auto want = first->read(all), got = again->read(all);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t n = 0; n < got.size(); ++n)
      ASSERT_TRUE(got[n] == want[n] || (std::isnan(got[n]) && std::isnan(want[n]))) << n;

    // Trace 20's CDP X moves 1000 m (scalar -100), and the file gets its old time back.
    const auto before = fs::last_write_time(path);
    {
      std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
      const std::streamoff at = s.trace0() + 20L * (SEGY_TRACE_HEADER_SIZE + 4L * s.ns) + SEGY_TR_CDP_X - 1;
      unsigned char b[4];
      f.seekg(at);
      f.read(reinterpret_cast<char*>(b), 4);
      std::uint32_t v = (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
      v += 100000;
      for (int k = 0; k < 4; ++k)
        b[k] = static_cast<unsigned char>(v >> (24 - 8 * k));
      f.seekp(at);
      f.write(reinterpret_cast<const char*>(b), 4);
    }
    fs::last_write_time(path, before);
    const SurveyAffine moved = open_volume(path, fill)->geometry().affine;
    EXPECT_GT(std::abs(moved.x0 - first->geometry().affine.x0), 1.0);
    EXPECT_EQ(open_volume(path, hinted)->geometry().affine, first->geometry().affine); // no pass over the headers

    fs::last_write_time(path, before + std::chrono::seconds(1));
    EXPECT_EQ(open_volume(path, hinted)->geometry().affine, moved);
    // Hints that do not fit are not used either.
    const std::string fresh_hint = open_volume(path, fill)->reopen_hint();
    std::string short_runs = fresh_hint;
    short_runs.replace(short_runs.find("\"runs\":[["), 9, "\"runs\":[[0,0,1,1],[");
    for (const std::string& bad : {std::string("not json"), std::string("{\"segy_grid\":{}}"), short_runs}) {
      OpenOptions o = fill;
      o.reopen_hint = bad;
      EXPECT_EQ(open_volume(path, o)->geometry(), open_volume(path, fill)->geometry()) << bad;
    }
    OpenOptions other_bytes = fill;
    other_bytes.reopen_hint = fresh_hint;
    other_bytes.segy = {9, 21};
    EXPECT_THROW(open_volume(path, other_bytes), FormatError); // the hint is for 189/193: the file is read at 9/21
  }
  // Holes everywhere (every third trace of 100 x 100): runs of one or two traces; the hint carries
  // the trace index itself (issue 54), which a worker then uses without the pass over the headers.
  SegySpec holes;
  holes.ni = holes.nj = 100;
  holes.ns = 8;
  for (int i = 0; i < holes.ni; ++i)
    for (int j = 0; j < holes.nj; ++j)
      if ((i * holes.nj + j) % 3 == 1) holes.missing.push_back({i, j});
  const std::string path = dir.file("holes.sgy");
  write_with_segyio(path, holes);
  const auto volume = open_volume(path, {.nan_policy = NanPolicy::fill});
  EXPECT_EQ(volume->geometry().shape, (Index3{100, 100, 8}));
  const std::string index_hint = volume->reopen_hint();
  EXPECT_NE(index_hint.find("\"index\":\"AAAAAP////8"), std::string::npos); // trace 0, then a hole
  EXPECT_NE(index_hint.find("\"runs\":[]"), std::string::npos);
  RecordingProgress worker_progress;
  OpenOptions worker{.nan_policy = NanPolicy::fill};
  worker.progress = &worker_progress;
  worker.reopen_hint = index_hint;
  const auto handed = open_volume(path, worker);
  EXPECT_TRUE(worker_progress.begun.empty()) << "the pass over the headers was made again";
  const std::vector<float> a = volume->read(volume->geometry().bounds()), b = handed->read(handed->geometry().bounds());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  // A damaged index (a trace placed twice) is not used: the pass is made.
  std::string damaged = index_hint;
  damaged.replace(damaged.find("\"index\":\"") + 9, 8, "AQAAAAEA"); // bins 0 and 1 both trace 1
  RecordingProgress again;
  worker.progress = &again;
  worker.reopen_hint = damaged;
  open_volume(path, worker);
  EXPECT_EQ(again.begun.size(), 1u);
}

} // namespace
