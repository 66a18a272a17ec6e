# Oracle tests of single-block extraction on analytic synthetic cubes (voxel components, full-
# resolution surface, planted volumes and azimuths) and degenerate inputs. Each case runs in well
# under 20 s in Release; the timeout leaves room for sanitizer builds.
geotandem_add_test(tandem_analytic_test
  SOURCES tandem_analytic_test.cpp ${PROJECT_SOURCE_DIR}/tests/support/voxel_components.cpp
  DEPS geotandem::tandem geotandem::synth geotandem::mesh geotandem::volume
  LABELS tandem TIMEOUT 300)
