# Simplifier and single-block tandem tests. The fixtures (an independent marching-tetrahedra layer
# source, analytic fields, a collecting sink) are shared by every executable.
add_library(geotandem_simplify_fixtures STATIC ${CMAKE_CURRENT_SOURCE_DIR}/simplify_fixtures.cpp)
target_link_libraries(geotandem_simplify_fixtures PUBLIC geotandem::tandem geotandem::mesh)
geotandem_target_defaults(geotandem_simplify_fixtures)

geotandem_add_test(simplify_units_test SOURCES simplify_units_test.cpp edge_queues_test.cpp region_test.cpp engine_parts_test.cpp
                   DEPS geotandem::tandem LABELS tandem)
# White-box tests of the internals (cost, heap, maps) see the part's private headers.
target_include_directories(simplify_units_test PRIVATE ${PROJECT_SOURCE_DIR}/framework/tandem/src)

geotandem_add_test(tandem_surface_test SOURCES tandem_surface_test.cpp DEPS geotandem_simplify_fixtures
                   LABELS tandem)
geotandem_add_test(tandem_sweep_test SOURCES tandem_sweep_test.cpp DEPS geotandem_simplify_fixtures LABELS tandem)
geotandem_add_test(tandem_constraints_test SOURCES tandem_constraints_test.cpp DEPS geotandem_simplify_fixtures
                   LABELS tandem)
geotandem_add_test(tandem_inputs_test SOURCES tandem_inputs_test.cpp DEPS geotandem_simplify_fixtures LABELS tandem)
geotandem_add_test(simplify_mesh_ops_test SOURCES simplify_mesh_ops_test.cpp
                   DEPS geotandem_simplify_fixtures OpenMeshCore LABELS tandem)
target_include_directories(simplify_mesh_ops_test PRIVATE ${PROJECT_SOURCE_DIR}/framework/tandem/src)
geotandem_add_test(tandem_block_test SOURCES tandem_block_test.cpp DEPS geotandem_simplify_fixtures LABELS tandem)
target_include_directories(tandem_block_test PRIVATE ${PROJECT_SOURCE_DIR}/framework/tandem/src)
# The E0 guarantee's per-collapse bound against sampled Hausdorff distances of random patches.
geotandem_add_test(collapse_distance_test SOURCES collapse_distance_test.cpp
                   DEPS geotandem::tandem geotandem::mesh OpenMeshCore LABELS tandem)
target_include_directories(collapse_distance_test PRIVATE ${PROJECT_SOURCE_DIR}/framework/tandem/src)
geotandem_add_test(tandem_extraction_options_test SOURCES extraction_options_test.cpp DEPS geotandem::tandem LABELS tandem)
