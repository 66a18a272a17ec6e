// Test helper for crash_test: commits the components of keys 1..N to a store through a LocalSink,
// in an order drawn from SEED, re-committing some keys on the way. The test SIGKILLs it at random
// moments. Usage: store_crash_writer STORE SEED BATCH N

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>

#include "fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/local_sink.hpp"

int main(int argc, char** argv) {
  using namespace geotandem;
  if (argc != 5) {
    std::cerr << "usage: store_crash_writer STORE SEED BATCH N\n";
    return 2;
  }
  try {
    const auto geometry = store::testing::test_geometry();
    const std::uint64_t seed = std::stoull(argv[2]), count = std::stoull(argv[4]);
    auto components = store::ComponentStore::open_or_create(argv[1], geometry, {"crash test", "store_crash_writer"});
    store::LocalSink sink(components, {"local", std::nullopt, std::stoul(argv[3])});
    // Tells the test that start-up (loading libraries, opening the store) is over.
    std::cout << "open" << std::endl;
    std::vector<std::uint64_t> keys;
    for (std::uint64_t key = 1; key <= count; ++key)
      keys.push_back(key);
    std::mt19937_64 rng(seed);
    std::shuffle(keys.begin(), keys.end(), rng);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      // Every tenth key is a larger surface, so that kills also land inside longer writes.
      sink.commit(store::testing::make_component(keys[i], geometry, keys[i] % 10 == 0 ? 3 : 1));
      if (i % 7 == 3) sink.commit(store::testing::make_component(keys[i / 2], geometry, keys[i / 2] % 10 == 0 ? 3 : 1));
    }
    sink.close();
    std::cout << "committed " << sink.committed() << "\n";
    return 0;
  } catch (const Error& e) {
    std::cerr << "store_crash_writer: " << e.what() << "\n";
    return 1;
  }
}
