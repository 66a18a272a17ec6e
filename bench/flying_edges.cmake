# bench_flying_edges_meshopt (issue 57, part 3): `geotandem extract --workers 0` against VTK's
# FlyingEdges3D plus meshoptimizer's meshopt_simplify to the same triangle count, one core, on a
# noisy cube the bench generates itself; times, triangle counts and Hausdorff distances to the
# full-resolution surface. VTK and meshoptimizer are bench-only dependencies, never installed by
# default (`GEOTANDEM_BENCH_DEPS=1 scripts/setup.sh` installs libvtk9-dev and libmeshoptimizer-dev):
# without them this bench is left out and the rest of the tree builds as before. Run it as
#   build/release/bin/bench_flying_edges_meshopt build/release/bin/geotandem [edge=512] [dir]
# or through bench/flying_edges_meshopt.sh.
find_package(VTK 9 QUIET COMPONENTS CommonCore CommonDataModel CommonExecutionModel FiltersCore)
find_package(meshoptimizer QUIET CONFIG)
if(NOT VTK_FOUND OR NOT meshoptimizer_FOUND)
  set(missing "")
  if(NOT VTK_FOUND)
    list(APPEND missing "VTK 9 (libvtk9-dev)")
  endif()
  if(NOT meshoptimizer_FOUND)
    list(APPEND missing "meshoptimizer (libmeshoptimizer-dev)")
  endif()
  list(JOIN missing " and " missing)
  message(STATUS "bench_flying_edges_meshopt left out: ${missing} not found (bench-only; "
                 "GEOTANDEM_BENCH_DEPS=1 scripts/setup.sh installs them)")
  return()
endif()
add_executable(bench_flying_edges_meshopt
  ${CMAKE_CURRENT_SOURCE_DIR}/flying_edges/flying_edges_meshopt.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/flying_edges/child_and_ply.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/flying_edges/noisy_cube.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/flying_edges/surface_distance.cpp)
# Imported targets: their headers are SYSTEM includes, so VTK's own warnings do not fail -Werror.
target_link_libraries(bench_flying_edges_meshopt PRIVATE VTK::CommonCore VTK::CommonDataModel
                                                         VTK::CommonExecutionModel VTK::FiltersCore
                                                         meshoptimizer::meshoptimizer)
target_include_directories(bench_flying_edges_meshopt PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
geotandem_target_defaults(bench_flying_edges_meshopt)
add_dependencies(bench_flying_edges_meshopt geotandem)
