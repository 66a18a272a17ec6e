#pragma once
// Component steps: they read the store's index (never the surfaces) and write named selections;
// the components themselves stay in the store (non-destructive).

#include <cstdint>
#include <string>
#include <vector>

#include "geotandem/store/store.hpp"

namespace geotandem::workflow {

struct BubbleRemoval {
  double min_volume = 0.0;            // absolute, world units
  double min_volume_fraction = 0.0;   // of the largest closed volume, [0, 1]
  double min_volume_percentile = 0.0; // of the closed volumes, [0, 100]
  std::uint64_t min_triangles = 0;
  // Keep components enclosing at least this many samples (mesh::ComponentStats::samples): the
  // unit-free alternative to min_volume (issue 54). 0: no rule. Refused on a store whose rows were
  // written before samples were counted.
  std::int64_t min_samples = 0;
  bool closed_only = false;       // drop components cut by the cube's border
  std::string from;               // selection to start from; empty: every component
  std::string selection = "kept"; // the selection written
};

struct BubbleResult {
  std::uint64_t before = 0;
  std::uint64_t after = 0;
  double threshold = 0.0;          // the volume threshold in force: the largest of the three volume rules
  std::vector<std::uint64_t> kept; // keys, largest volume first
};

// Keeps a component when its volume reaches the threshold and it has enough triangles. A component
// cut by the cube's border has no enclosed volume; it is kept when the area of its part inside the
// cube reaches the area of a sphere of the threshold volume (by the isoperimetric inequality no
// body smaller than the threshold has that much surface), unless closed_only. Volumes are signed:
// a volume rule drops the inner surface of a hollow body (negative volume); with no volume rule
// set, no component is dropped for its volume.
// Throws InvalidArgument for out-of-range rules or an unknown `from` selection.
BubbleResult remove_bubbles(store::ComponentStore& store, const BubbleRemoval& rules);

struct AzimuthSorting {
  int bins = 18;            // over [0, 180)
  double azimuth_min = 0.0; // keep azimuths in [min, max] (axial degrees; min > max wraps past 180)
  double azimuth_max = 180.0;
  std::string from; // selection to start from; empty: the newest selection, else everything
  std::string selection = "sorted";
};

struct AzimuthResult {
  std::uint64_t before = 0;
  std::uint64_t after = 0;
  std::vector<std::uint64_t> histogram; // counts per bin over [0, 180)
  double mean_azimuth = 0.0;            // axial mean by angle doubling, weighted by volume
  double resultant_length = 0.0;        // of the doubled angles, [0, 1]: 1 = all parallel
  // Keys in the azimuth range ranked by bin population (the dominant direction first), then by
  // volume within a bin.
  std::vector<std::uint64_t> ranking;
};

AzimuthResult sort_by_azimuth(store::ComponentStore& store, const AzimuthSorting& rules);

} // namespace geotandem::workflow
