set(TANDEM_MC_SOURCES src/lattice.cpp src/mc_table.cpp src/marching_cubes.cpp src/mc_caps.cpp src/mc_cap_layers.cpp src/slab_reader.cpp src/mc_surface.cpp src/block_tree.cpp)
