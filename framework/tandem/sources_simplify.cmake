# Working surface, Attali cost, queues, time lag, components, the single-block tandem loop.
set(TANDEM_SIMPLIFY_SOURCES
  src/attali_cost.cpp
  src/collapse_ops.cpp
  src/collapse_distance.cpp
  src/component_reader.cpp
  src/component_table.cpp
  src/region.cpp
  src/spare_meshes.cpp
  src/surface_engine.cpp
  src/edge_cost.cpp
  src/triangle_insert.cpp
  src/surface_layers.cpp
  src/surface_dump.cpp
  src/working_mesh.cpp
  src/working_surface.cpp
  src/tandem_driver.cpp
  src/extraction_options.cpp)
