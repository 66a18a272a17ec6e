#include "e2e_support.hpp"

#include <sys/resource.h>

#include "test_paths.hpp"
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

namespace geotandem::testing {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Margins of the centroid match: detected bodies are fatter than the planted ones by about a
// wavelet (11 samples each way at 30 Hz, the chaos filters add a few traces).
constexpr double margin_ij = 4.0;
constexpr double margin_k = 8.0;

// CPU time of every waited-for child so far (the shell std::system starts, and its geotandem).
double children_cpu_seconds() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

} // namespace

WorkflowRun run_workflow(const std::string& recipe, const std::filesystem::path& out,
                         const std::vector<std::string>& sets, const std::string& extra) {
  std::string args = "run-workflow " + quoted(recipe) + " --set " + quoted("output.directory=" + out.string());
  for (const auto& s : sets)
    args += " --set " + quoted(s);
  if (!extra.empty()) args += " " + extra;
  auto start = std::chrono::steady_clock::now();
  double cpu_before = children_cpu_seconds();
  WorkflowRun run;
  run.command = run_geotandem(args);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_seconds = children_cpu_seconds() - cpu_before;
  return run;
}

std::string workflow_recipe(const std::string& name) {
  return test_paths::workflows() + "/" + name;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<PlantedBody> planted_bodies(const nlohmann::json& truth) {
  std::vector<PlantedBody> bodies;
  for (const auto& b : truth.at("bodies")) {
    PlantedBody p;
    p.name = b.at("name");
    p.type = b.at("type");
    p.azimuth = b.at("azimuth_deg");
    p.volume = b.at("volume_world");
    for (int a = 0; a < 3; ++a) {
      p.lo[a] = b.at("bounds_index").at("lo").at(a);
      p.hi[a] = b.at("bounds_index").at("hi").at(a);
    }
    p.chaotic = b.at("chaotic");
    p.negative_control = b.at("negative_control");
    p.cut_by_border = b.at("cut_by_border");
    for (const auto& [name, value] : b.at("dimensions").items())
      p.dimensions[name] = value.get<double>();
    bodies.push_back(p);
  }
  return bodies;
}

double principal_azimuth(const PlantedBody& body) {
  if (body.type != "channel") return body.azimuth;
  const auto& d = body.dimensions;
  const double half = d.at("half_length"), a = d.at("amplitude"), width = d.at("half_width");
  const double k = 2.0 * std::numbers::pi / d.at("wavelength"), phase = d.at("phase");
  // Local coordinates: s along the axis u (the planted azimuth), n along v (u turned 90 degrees
  // clockwise, as the synthetic model lays out its lines).
  constexpr int steps = 2000;
  double w = 0, ms = 0, mn = 0;
  std::vector<std::array<double, 5>> samples; // s, n, weight, normal s, normal n
  for (int i = 0; i <= steps; ++i) {
    double t = -half + 2.0 * half * i / steps;
    double n = a * std::sin(k * t + phase), slope = a * k * std::cos(k * t + phase);
    double ds = std::sqrt(1.0 + slope * slope);
    samples.push_back({t, n, ds, -slope / ds, 1.0 / ds});
    w += ds;
    ms += t * ds;
    mn += n * ds;
  }
  ms /= w;
  mn /= w;
  const double across = width * width / 3.0; // variance of a uniform band of half width `width`
  double css = 0, cnn = 0, csn = 0;
  for (const auto& [s, n, ds, ns, nn] : samples) {
    css += ds * ((s - ms) * (s - ms) + across * ns * ns);
    cnn += ds * ((n - mn) * (n - mn) + across * nn * nn);
    csn += ds * ((s - ms) * (n - mn) + across * ns * nn);
  }
  double turn = 0.5 * std::atan2(2.0 * csn, css - cnn) * 180.0 / std::numbers::pi;
  return std::fmod(std::fmod(body.azimuth + turn, 180.0) + 180.0, 180.0);
}

std::array<double, 3> to_index(const nlohmann::json& truth, const std::array<double, 3>& world) {
  const auto& g = truth.at("geometry");
  const auto& a = g.at("affine");
  double x0 = a.at("x0"), xi = a.at("xi"), xj = a.at("xj"), y0 = a.at("y0"), yi = a.at("yi"), yj = a.at("yj");
  double dx = world[0] - x0, dy = world[1] - y0, det = xi * yj - xj * yi;
  double z0 = g.at("z0"), dz = g.at("dz");
  return {(dx * yj - xj * dy) / det, (xi * dy - yi * dx) / det, (world[2] - z0) / dz};
}

bool inside(const PlantedBody& body, const std::array<double, 3>& index, double mij, double mk) {
  for (int a = 0; a < 3; ++a) {
    double m = a < 2 ? mij : mk;
    if (index[a] < body.lo[a] - m || index[a] > body.hi[a] + m) return false;
  }
  return true;
}

const PlantedBody* body_of(const std::vector<PlantedBody>& bodies, const nlohmann::json& truth,
                           const store::ComponentRow& row) {
  auto at = to_index(truth, row.stats.centroid);
  const PlantedBody* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& b : bodies) {
    if (!inside(b, at, margin_ij, margin_k)) continue;
    double d = 0;
    for (int a = 0; a < 3; ++a)
      d += std::pow(at[a] - 0.5 * (b.lo[a] + b.hi[a]), 2);
    if (d < best_d) {
      best_d = d;
      best = &b;
    }
  }
  return best;
}

} // namespace geotandem::testing
