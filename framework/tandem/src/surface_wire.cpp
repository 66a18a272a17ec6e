// The wire form of a working surface (serialize.hpp; layout in docs/algorithm.md): a fixed header
// (magic, version, flags, payload length, XXH64 of the payload) and the payload, the fields of a
// SurfaceState in a fixed order, little-endian, without padding.
#include "geotandem/tandem/serialize.hpp"

#include <xxhash.h>

#include <bit>
#include <string>

#include "geotandem/core/error.hpp"
#include "surface_check.hpp"
#include "surface_engine.hpp"
#include "wire_io.hpp"

namespace geotandem::tandem {

static_assert(std::endian::native == std::endian::little, "the wire format is little-endian");

namespace detail {

// Friend of WorkingSurface: reaches the engine to export and import its state.
struct SurfaceAccess {
  static SurfaceState state(const WorkingSurface& s) { return s.engine_->export_state(); }
  static std::size_t merge(WorkingSurface& into, SurfaceState&& state, const CancelToken* cancel) {
    return into.engine_->merge_state(std::move(state), cancel);
  }
  static WorkingSurface make(SurfaceState&& state, mesh::ComponentSink* sink, CollapseObserver* observer) {
    auto engine =
        std::make_unique<WorkingSurface::Engine>(state.cube, state.region, state.axis, state.options, sink, observer);
    engine->import_state(std::move(state));
    return WorkingSurface(std::move(engine));
  }
};

} // namespace detail

namespace {

using detail::Reader;
using detail::Writer;

constexpr char kMagic[8] = {'G', 'T', 'W', 'S', 'U', 'R', 'F', 'L'}; // L: little-endian

void put_box(Writer& w, const volume::Box& b) {
  for (int a = 0; a < 3; ++a)
    w.put(b.lo[a]);
  for (int a = 0; a < 3; ++a)
    w.put(b.hi[a]);
}
volume::Box get_box(Reader& r) {
  volume::Box b;
  for (int a = 0; a < 3; ++a)
    b.lo[a] = r.get<std::int64_t>();
  for (int a = 0; a < 3; ++a)
    b.hi[a] = r.get<std::int64_t>();
  // Cells of a cube of at most 2^30 samples an axis (surface_check.cpp): the region's arithmetic
  // on boxes (extents, counts) cannot overflow then.
  for (int a = 0; a < 3; ++a)
    if (b.lo[a] < 0 || b.lo[a] > (std::int64_t{1} << 30) || b.hi[a] < 0 || b.hi[a] > (std::int64_t{1} << 30))
      throw DataError("working-surface record: the box " + std::to_string(b.lo[a]) + ":" + std::to_string(b.hi[a]) +
                      " along axis " + std::to_string(a) + " of its region is outside [0, 2^30]");
  return b;
}

void put_counters(Writer& w, const SimplifyCounters& c) {
  for (auto field : SimplifyCounters::all)
    w.put(c.*field);
}
SimplifyCounters get_counters(Reader& r) {
  SimplifyCounters c;
  for (auto field : SimplifyCounters::all)
    c.*field = r.get<std::uint64_t>();
  return c;
}

// Bytes per item, for the count checks.
constexpr std::size_t kVertexBytes = std::size_t{16} * 8 + 8 + 4 + 1 + 4;
constexpr std::size_t kFaceBytes = std::size_t{3} * 4;
constexpr std::size_t kEdgeBytes = 4 + 4 + 1 + 1 + 4 + 8 + std::size_t{3} * 8;

void encode(Writer& w, const detail::SurfaceState& s) {
  // Geometry of the cube.
  const volume::Geometry& g = s.cube;
  for (int a = 0; a < 3; ++a)
    w.put(g.shape[a]);
  for (double v : {g.inline0, g.inline_step, g.crossline0, g.crossline_step, g.z0, g.dz})
    w.put(v);
  w.put(static_cast<std::uint8_t>(g.z_unit));
  for (double v : {g.affine.x0, g.affine.xi, g.affine.xj, g.affine.y0, g.affine.yi, g.affine.yj})
    w.put(v);
  // Axis and options.
  w.put(static_cast<std::int32_t>(s.axis));
  w.put(s.options.max_error);
  w.put(s.options.isotropy);
  w.put(static_cast<std::uint8_t>((s.options.time_lag ? 1u : 0u) | (s.options.extended_time_lag ? 2u : 0u) |
                                  (s.options.preserve_volume ? 4u : 0u) | (s.options.guarantee_distance ? 8u : 0u)));
  w.put(static_cast<std::uint64_t>(s.options.compaction_min_dead));
  // Region.
  put_box(w, s.region.cube());
  w.count(s.region.blocks().size());
  for (const volume::Box& b : s.region.blocks())
    put_box(w, b);
  // Sweep and counters.
  w.put(s.front);
  w.put(s.last_rank);
  w.put(s.origin);
  put_counters(w, s.counters);
  // Components.
  w.count(s.component_keys.size());
  for (std::uint64_t k : s.component_keys)
    w.put(k);
  // Vertices.
  w.count(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const detail::StateVertex& v = s.vertices[i];
    w.put(s.points[i]);
    for (double x : v.shape.m)
      w.put(x);
    w.put(v.height);
    w.put(v.rad);
    w.put(v.tolerance);
    w.put(v.lattice_id);
    w.put(static_cast<std::int32_t>(v.component));
    w.put(v.border);
    w.put(v.version);
  }
  // Triangles.
  w.count(s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    for (std::uint32_t v : s.triangles[t])
      w.put(v);
  }
  // Edges that are not idle.
  w.count(s.edges.size());
  for (const detail::StateEdge& e : s.edges) {
    w.put(e.v0);
    w.put(e.v1);
    w.put(static_cast<std::uint8_t>(e.state));
    w.put(static_cast<std::uint8_t>((e.pending.retried ? 1u : 0u) | (e.pending.dirty ? 2u : 0u)));
    w.put(e.pending.stamp);
    w.put(e.key);
    w.put(e.pending.target);
  }
  // The last layer's ids and its unused vertices.
  w.count(s.previous_ids.size());
  for (const auto& [id, v] : s.previous_ids) {
    w.put(id);
    w.put(v);
  }
  w.count(s.isolated.size());
  for (std::uint32_t v : s.isolated)
    w.put(v);
  // Flag kFlagComponentSamples: the samples each component encloses so far (issue 54), last, so
  // that the sections before keep their offsets.
  w.count(s.component_samples.size());
  for (std::int64_t n : s.component_samples)
    w.put(n);
}

detail::SurfaceState decode(Reader& r, std::uint32_t record_flags) {
  detail::SurfaceState s;
  volume::Geometry& g = s.cube;
  for (int a = 0; a < 3; ++a)
    g.shape[a] = r.get<std::int64_t>();
  for (double* v : {&g.inline0, &g.inline_step, &g.crossline0, &g.crossline_step, &g.z0, &g.dz})
    *v = r.get<double>();
  const auto unit = r.get<std::uint8_t>();
  if (unit > static_cast<std::uint8_t>(volume::SampleUnit::feet))
    throw DataError("working-surface record: unknown sample unit " + std::to_string(unit));
  g.z_unit = static_cast<volume::SampleUnit>(unit);
  for (double* v : {&g.affine.x0, &g.affine.xi, &g.affine.xj, &g.affine.y0, &g.affine.yi, &g.affine.yj})
    *v = r.get<double>();

  s.axis = r.get<std::int32_t>();
  s.options.max_error = r.get<double>();
  s.options.isotropy = r.get<double>();
  const auto flags = r.get<std::uint8_t>();
  s.options.time_lag = (flags & 1u) != 0;
  s.options.extended_time_lag = (flags & 2u) != 0;
  s.options.preserve_volume = (flags & 4u) != 0;
  s.options.guarantee_distance = (flags & 8u) != 0;
  s.options.compaction_min_dead = static_cast<std::size_t>(r.get<std::uint64_t>());

  const volume::Box cube = get_box(r);
  std::vector<volume::Box> blocks(r.count(48, "blocks"));
  for (volume::Box& b : blocks)
    b = get_box(r);
  try {
    s.region = Region(cube, std::move(blocks));
  } catch (const InvalidArgument& e) {
    throw DataError("working-surface record: invalid region: " + e.message());
  }

  s.front = r.get<double>();
  s.last_rank = r.get<std::int64_t>();
  s.origin = r.vec();
  s.counters = get_counters(r);

  s.component_keys.resize(r.count(8, "components"));
  for (std::uint64_t& k : s.component_keys)
    k = r.get<std::uint64_t>();

  const std::size_t nv = r.count(kVertexBytes, "vertices");
  s.points.resize(nv);
  s.vertices.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    detail::StateVertex& v = s.vertices[i];
    s.points[i] = r.vec();
    for (double& x : v.shape.m)
      x = r.get<double>();
    v.height = r.get<double>();
    v.rad = r.get<double>();
    v.tolerance = r.get<double>();
    if (!(v.tolerance >= 0.0 && v.tolerance <= s.options.max_error))
      throw DataError("working-surface record: vertex " + std::to_string(i) + " has distance bound " +
                      std::to_string(v.tolerance) + ", outside [0, E0]");
    v.lattice_id = r.get<std::uint64_t>();
    v.component = r.get<std::int32_t>();
    v.border = r.get<std::uint8_t>();
    v.version = r.get<std::uint32_t>();
  }

  const std::size_t nt = r.count(kFaceBytes, "triangles");
  s.triangles.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    for (std::uint32_t& v : s.triangles[t])
      v = r.get<std::uint32_t>();
  }

  s.edges.resize(r.count(kEdgeBytes, "edges"));
  for (detail::StateEdge& e : s.edges) {
    e.v0 = r.get<std::uint32_t>();
    e.v1 = r.get<std::uint32_t>();
    const auto state = r.get<std::uint8_t>();
    if (state > static_cast<std::uint8_t>(detail::EdgeState::parked))
      throw DataError("working-surface record: unknown edge state " + std::to_string(state));
    e.state = static_cast<detail::EdgeState>(state);
    const auto edge_flags = r.get<std::uint8_t>();
    e.pending.retried = (edge_flags & 1u) != 0;
    e.pending.dirty = (edge_flags & 2u) != 0;
    e.pending.stamp = r.get<std::uint32_t>();
    e.key = r.get<double>();
    e.pending.target = r.vec();
  }

  s.previous_ids.resize(r.count(12, "last-layer ids"));
  for (auto& [id, v] : s.previous_ids) {
    id = r.get<std::uint64_t>();
    v = r.get<std::uint32_t>();
  }
  s.isolated.resize(r.count(4, "isolated vertices"));
  for (std::uint32_t& v : s.isolated)
    v = r.get<std::uint32_t>();
  if (record_flags & kFlagComponentSamples) {
    s.component_samples.resize(r.count(8, "component samples"));
    for (std::int64_t& n : s.component_samples)
      n = r.get<std::int64_t>();
  }
  if (!r.done())
    throw DataError("working-surface record: " + std::to_string(r.offset()) +
                    " payload bytes decoded but the header announces more");
  return s;
}

std::string hex(std::uint64_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4)
    s[static_cast<std::size_t>(i)] = kDigits[v & 15u];
  return s;
}

std::vector<std::byte> record_of(const detail::SurfaceState& state) {
  Writer w;
  // The room the record needs, at most a few kilobytes over (the fixed fields are not counted
  // exactly): a record grown by doubling would be held twice while it moves.
  w.reserve(kSurfaceWireHeaderSize + 4096 + 48 * state.region.blocks().size() + 8 * state.component_keys.size() +
            kVertexBytes * state.points.size() + kFaceBytes * state.triangles.size() + kEdgeBytes * state.edges.size() +
            12 * state.previous_ids.size() + 4 * state.isolated.size());
  for (char c : kMagic)
    w.put(static_cast<std::uint8_t>(c));
  w.put(kSurfaceWireVersion);
  w.put(kFlagComponentSamples); // flags
  w.put(std::uint64_t{0});      // payload length, filled in below
  w.put(std::uint64_t{0});      // checksum, filled in below
  encode(w, state);
  std::vector<std::byte>& out = w.bytes();
  const std::uint64_t length = out.size() - kSurfaceWireHeaderSize;
  const std::uint64_t hash = XXH64(out.data() + kSurfaceWireHeaderSize, length, 0);
  std::memcpy(out.data() + 16, &length, 8);
  std::memcpy(out.data() + 24, &hash, 8);
  return std::move(out);
}
} // namespace

std::vector<std::byte> serialize(const WorkingSurface& surface) {
  return record_of(detail::SurfaceAccess::state(surface));
}

std::vector<std::byte> serialize(WorkingSurface&& surface) {
  const detail::SurfaceState state = detail::SurfaceAccess::state(surface);
  { const WorkingSurface gone(std::move(surface)); } // its storage goes before the record is built
  return record_of(state);
}

namespace {

// The record's header checked and its payload decoded (deserialize, merge_record).
detail::SurfaceState decode_record(std::span<const std::byte> record) {
  if (record.size() < kSurfaceWireHeaderSize)
    throw DataError("working-surface record: " + std::to_string(record.size()) + " bytes, shorter than its " +
                        std::to_string(kSurfaceWireHeaderSize) + "-byte header (truncated)",
                    {}, "the record was cut in transit or in storage: ship it again");
  if (std::memcmp(record.data(), kMagic, sizeof(kMagic)) != 0)
    throw DataError("working-surface record: wrong magic (not a geotandem working-surface record, or not "
                    "little-endian)");
  Reader header(record.subspan(8, kSurfaceWireHeaderSize - 8));
  const auto version = header.get<std::uint32_t>();
  const auto flags = header.get<std::uint32_t>();
  const auto length = header.get<std::uint64_t>();
  const auto hash = header.get<std::uint64_t>();
  if (version != kSurfaceWireVersion)
    throw DataError("working-surface record: format version " + std::to_string(version) + ", this build reads " +
                        std::to_string(kSurfaceWireVersion),
                    {}, "run the same geotandem version on the manager and every worker");
  if ((flags & ~kFlagComponentSamples) != 0)
    throw DataError("working-surface record: unknown flags " + std::to_string(flags));
  const std::size_t present = record.size() - kSurfaceWireHeaderSize;
  if (length != present)
    throw DataError("working-surface record: the header announces " + std::to_string(length) + " payload bytes but " +
                        std::to_string(present) + " follow" + (length > present ? " (truncated)" : " (trailing bytes)"),
                    {}, "the record was cut or padded in transit or in storage");
  const std::span<const std::byte> payload = record.subspan(kSurfaceWireHeaderSize);
  const std::uint64_t actual = XXH64(payload.data(), payload.size(), 0);
  if (actual != hash)
    throw DataError("working-surface record: checksum mismatch (XXH64 " + hex(actual) + ", header says " + hex(hash) +
                        "): the record is corrupt",
                    {}, "the record was damaged in transit or in storage: ship it again");
  Reader r(payload);
  detail::SurfaceState state = decode(r, flags);
  detail::check_state(state); // the checksum says the bytes arrived; this, that they make a surface
  return state;
}

} // namespace

WorkingSurface deserialize(std::span<const std::byte> record, mesh::ComponentSink* sink, CollapseObserver* observer) {
  detail::SurfaceState state = decode_record(record);
  try {
    return detail::SurfaceAccess::make(std::move(state), sink, observer);
  } catch (const InvalidArgument& e) {
    throw DataError("working-surface record: " + e.message());
  }
}

namespace {
std::size_t merge_state(WorkingSurface& into, detail::SurfaceState&& state, const CancelToken* cancel) {
  try {
    return detail::SurfaceAccess::merge(into, std::move(state), cancel);
  } catch (const InvalidArgument& e) {
    throw DataError("working-surface record: " + e.message());
  }
}
} // namespace

std::size_t merge_record(WorkingSurface& into, std::span<const std::byte> record, const CancelToken* cancel) {
  return merge_state(into, decode_record(record), cancel);
}

std::size_t merge_record(WorkingSurface& into, std::vector<std::byte>&& record, const CancelToken* cancel) {
  detail::SurfaceState state = decode_record(record);
  std::vector<std::byte>().swap(record); // given back before the surface grows
  return merge_state(into, std::move(state), cancel);
}

} // namespace geotandem::tandem
