# Partial surfaces as plain data, their wire form, merging, and the in-process block-tree driver.
set(TANDEM_BLOCKS_SOURCES
  src/surface_state.cpp
  src/surface_check.cpp
  src/surface_merge.cpp
  src/surface_wire.cpp
  src/blocks_driver.cpp)
