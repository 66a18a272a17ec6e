#include "store_filters.hpp"

#include "command.hpp"

namespace geotandem::app {

void Filters::add_to(CLI::App* cmd) {
  min_volume_opt =
      cmd->add_option("--min-volume", min_volume, "smallest enclosed volume (world units)")->check(not_nan());
  max_volume_opt =
      cmd->add_option("--max-volume", max_volume, "largest enclosed volume (world units)")->check(not_nan());
  cmd->add_option("--azimuth", azimuth, "azimuth range A:B in degrees from north, axial; 170:10 wraps past north");
  cmd->add_option("--box", box, "world box x0,y0,z0,x1,y1,z1 that the component's bounding box must meet");
  min_triangles_opt = cmd->add_option("--min-triangles", min_triangles, "fewest triangles")->check(not_negative());
  max_triangles_opt = cmd->add_option("--max-triangles", max_triangles, "most triangles")->check(not_negative());
  min_vertices_opt = cmd->add_option("--min-vertices", min_vertices, "fewest vertices")->check(not_negative());
  max_vertices_opt = cmd->add_option("--max-vertices", max_vertices, "most vertices")->check(not_negative());
  cmd->add_flag("--closed", closed, "closed surfaces only (not cut by the cube border)");
  cmd->add_option("--selection,--select", selection, "members of this named selection only (e.g. kept, sorted)");
  cmd->add_option("--sort", sort, "key, volume (largest first), azimuth, or selection (the selection's own order)")
      ->capture_default_str();
  cmd->add_flag("--reverse", reverse, "reverse the sort order");
  limit_opt = cmd->add_option("--limit", limit, "at most this many components")->check(not_negative());
}

store::Query Filters::query() const {
  store::Query q;
  if (min_volume_opt->count()) q.min_volume = min_volume;
  if (max_volume_opt->count()) q.max_volume = max_volume;
  if (!azimuth.empty()) q.azimuth = store::parse_azimuth_range(azimuth);
  if (!box.empty()) q.box = store::parse_world_box(box);
  if (min_triangles_opt->count()) q.min_triangles = min_triangles;
  if (max_triangles_opt->count()) q.max_triangles = max_triangles;
  if (min_vertices_opt->count()) q.min_vertices = min_vertices;
  if (max_vertices_opt->count()) q.max_vertices = max_vertices;
  q.closed_only = closed;
  q.selection = selection;
  q.sort = store::parse_sort_key(sort);
  // Volumes are wanted largest first; every other order reads naturally ascending.
  q.descending = (q.sort == store::SortKey::volume) != reverse;
  if (limit_opt->count()) q.limit = limit;
  return q;
}

} // namespace geotandem::app
