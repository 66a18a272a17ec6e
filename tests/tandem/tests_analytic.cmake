# Oracle tests of single-block extraction on analytic synthetic cubes (voxel components, full-
# resolution surface, planted volumes and azimuths); degenerate inputs apart. Each case runs in well
# under 20 s in Release; the timeout leaves room for sanitizer builds.
geotandem_add_test(tandem_analytic_test
  SOURCES tandem_analytic_test.cpp ${PROJECT_SOURCE_DIR}/tests/support/voxel_components.cpp
  DEPS geotandem_simplify_fixtures geotandem::synth geotandem::mesh geotandem::volume
  LABELS tandem TIMEOUT 300)
geotandem_add_test(tandem_degenerate_test SOURCES tandem_degenerate_test.cpp
  DEPS geotandem_simplify_fixtures geotandem::mesh geotandem::volume LABELS tandem)
# The E0 guarantee: symmetric Hausdorff distance to full-resolution marching cubes <= E0 for every
# component, E0 = 0.25, 0.5, 1, in 1 and 64 blocks, clean and noisy analytic cubes (seconds each).
geotandem_add_test(tandem_guarantee_test SOURCES tandem_guarantee_test.cpp
  DEPS geotandem_simplify_fixtures geotandem::synth geotandem::mesh geotandem::volume
  LABELS tandem TIMEOUT 300)
geotandem_add_test(tandem_caps_test
  SOURCES tandem_caps_test.cpp ${PROJECT_SOURCE_DIR}/tests/support/voxel_components.cpp
  DEPS geotandem_simplify_fixtures geotandem::mesh geotandem::volume LABELS tandem TIMEOUT 300)
