# marching cubes and block tree tests
geotandem_add_test(tandem_mc_test SOURCES mc_topology_test.cpp mc_blocks_test.cpp
  DEPS geotandem::tandem geotandem::mesh)
geotandem_add_test(tandem_block_tree_test SOURCES block_tree_test.cpp DEPS geotandem::tandem)
