# Every third-party dependency, found once. All come from Debian 12 packages (scripts/setup.sh).
find_package(Threads REQUIRED)
find_package(GDAL CONFIG REQUIRED)
find_package(OpenMesh REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(SQLite3 REQUIRED)
find_package(ZLIB REQUIRED)
find_package(cppzmq REQUIRED) # libzmq3-dev, cppzmq-dev: private to geotandem::runtime

# Debian's segyio package config names a library file for no build configuration; wrap the header
# and library ourselves.
find_path(SEGYIO_INCLUDE_DIR segyio/segy.h REQUIRED)
find_library(SEGYIO_LIBRARY segyio REQUIRED)
if(NOT TARGET segyio::segyio)
  add_library(segyio::segyio UNKNOWN IMPORTED)
  set_target_properties(segyio::segyio PROPERTIES
    IMPORTED_LOCATION "${SEGYIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SEGYIO_INCLUDE_DIR}")
endif()

# libxxhash-dev ships no CMake package: wrap its header and library in an imported target.
find_path(XXHASH_INCLUDE_DIR xxhash.h REQUIRED)
find_library(XXHASH_LIBRARY xxhash REQUIRED)
if(NOT TARGET xxhash::xxhash)
  add_library(xxhash::xxhash UNKNOWN IMPORTED)
  set_target_properties(xxhash::xxhash PROPERTIES
    IMPORTED_LOCATION "${XXHASH_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${XXHASH_INCLUDE_DIR}")
endif()

if(GEOTANDEM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
