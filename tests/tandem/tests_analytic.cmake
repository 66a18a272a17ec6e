# Oracle tests of single-block extraction on analytic synthetic cubes (voxel components, full-
# resolution surface, planted volumes and azimuths); degenerate inputs apart. Each case runs in well
# under 20 s in Release; the timeout leaves room for sanitizer builds.
geotandem_add_test(tandem_analytic_test
  SOURCES tandem_analytic_test.cpp ${PROJECT_SOURCE_DIR}/tests/support/voxel_components.cpp
  DEPS geotandem_simplify_fixtures geotandem::synth geotandem::mesh geotandem::volume
  LABELS tandem TIMEOUT 300)
geotandem_add_test(tandem_degenerate_test SOURCES tandem_degenerate_test.cpp
  DEPS geotandem_simplify_fixtures geotandem::mesh geotandem::volume LABELS tandem)
geotandem_add_test(tandem_caps_test
  SOURCES tandem_caps_test.cpp ${PROJECT_SOURCE_DIR}/tests/support/voxel_components.cpp
  DEPS geotandem_simplify_fixtures geotandem::mesh geotandem::volume LABELS tandem TIMEOUT 300)
