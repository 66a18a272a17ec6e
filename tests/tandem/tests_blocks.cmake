# Blocks, merging and the wire format of partial surfaces.
geotandem_add_test(tandem_blocks_test SOURCES tandem_blocks_test.cpp DEPS geotandem_simplify_fixtures LABELS tandem)
geotandem_add_test(tandem_serialize_test SOURCES tandem_serialize_test.cpp
                   DEPS geotandem_simplify_fixtures xxhash::xxhash LABELS tandem)
geotandem_add_test(tandem_merge_record_test SOURCES tandem_merge_record_test.cpp
                   DEPS geotandem_simplify_fixtures LABELS tandem)
geotandem_add_test(tandem_record_mutation_test SOURCES tandem_record_mutation_test.cpp
                   DEPS geotandem_simplify_fixtures geotandem_testing xxhash::xxhash LABELS tandem TIMEOUT 1200)
