#pragma once
// Helpers of the end-to-end workflow tests: run `geotandem run-workflow` as a child process, read
// the ground truth a synthetic input leaves beside the store, and match store components to the
// planted bodies.

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/store/store.hpp"
#include "scratch.hpp"

namespace geotandem::testing {

struct WorkflowRun {
  CommandResult command;
  double seconds = 0.0;     // wall time of the child process
  double cpu_seconds = 0.0; // its user + system CPU time: steadier than wall time on a busy machine
};

// Runs `geotandem run-workflow RECIPE --set output.directory=OUT --set ... EXTRA`.
WorkflowRun run_workflow(const std::string& recipe, const std::filesystem::path& out,
                         const std::vector<std::string>& sets = {}, const std::string& extra = "");

// workflows/NAME.
std::string workflow_recipe(const std::string& name);

nlohmann::json read_json(const std::filesystem::path& path);
// A file's whole content (empty when it cannot be read: the assertions on it then fail).
std::string read_text(const std::filesystem::path& path);

// A planted body of the ground truth JSON, with what the matching needs.
struct PlantedBody {
  std::string name;
  std::string type;
  double azimuth = 0.0;
  double volume = 0.0;              // world units, the whole body (also outside the cube when cut by the border)
  std::array<double, 3> lo{}, hi{}; // fractional index box
  bool chaotic = false;
  bool negative_control = false;
  bool cut_by_border = false;
  std::map<std::string, double> dimensions; // body-frame units (docs/synthetic.md)
};

std::vector<PlantedBody> planted_bodies(const nlohmann::json& truth);

// The azimuth the main horizontal axis of the planted body itself has (what a principal-axis
// measure of a perfect detection gives). For lobes and other symmetric shapes it is the planted
// azimuth. For a sinuous channel the truth's azimuth is the direction of the centre line's axis;
// when the channel spans less than a whole meander the line is not symmetric about that axis and
// its principal axis turns by up to several degrees: computed here from the truth's dimensions
// (centre line A sin(2 pi t / wavelength + phase) across the axis, t in [-half_length,
// half_length], weighted by arc length, plus the channel's half width across the line).
double principal_azimuth(const PlantedBody& body);

// World (x, y, z) to fractional index (i, j, k) through the truth's survey affine.
std::array<double, 3> to_index(const nlohmann::json& truth, const std::array<double, 3>& world);

// True when `index` lies in the body's index box grown by `margin_ij` traces horizontally and
// `margin_k` samples vertically (detected bodies are fatter than planted ones by about a wavelet).
bool inside(const PlantedBody& body, const std::array<double, 3>& index, double margin_ij, double margin_k);

// The planted body whose (grown) box holds the component's centroid; nullptr when none. When
// several do, the one whose box centre is nearest.
const PlantedBody* body_of(const std::vector<PlantedBody>& bodies, const nlohmann::json& truth,
                           const store::ComponentRow& row);

} // namespace geotandem::testing
