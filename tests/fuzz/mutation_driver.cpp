// A fuzz driver for builds without libFuzzer (GCC's sanitizer presets): it runs every seed, then
// random mutations of the seeds through LLVMFuzzerTestOneInput for a bounded time. It is not
// coverage-guided (tests/fuzz/run_fuzz.sh runs the same targets under clang's libFuzzer for that);
// it exists so that CI runs the fuzz targets under the address and undefined-behaviour sanitizers
// on every change, with the project's own files as seeds.
//
//   fuzz_TARGET_driver SECONDS SEED_FILE_OR_DIRECTORY...
//
// Mutations: byte flips, random bytes, interesting integers written at random offsets, runs
// inserted, deleted or repeated, truncation, and splices of two seeds. The generator's seed comes
// from GEOTANDEM_FUZZ_SEED (default 1), so a run is repeatable. Before each input is tried it is
// written to GEOTANDEM_FUZZ_LAST (when set), so the input of a crash is there afterwards.

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::size_t max_input = 1u << 20;

Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

std::vector<Bytes> load_seeds(int argc, char** argv) {
  std::vector<Bytes> seeds;
  for (int i = 2; i < argc; ++i) {
    std::filesystem::path p = argv[i];
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::directory_iterator(p))
        if (e.is_regular_file()) seeds.push_back(read_file(e.path()));
    } else if (std::filesystem::is_regular_file(p)) {
      seeds.push_back(read_file(p));
    } else {
      std::cerr << "fuzz driver: no seed file or directory " << p << "\n";
      std::exit(2);
    }
  }
  return seeds;
}

class Mutator {
public:
  Mutator(const std::vector<Bytes>& seeds, std::uint64_t seed) : seeds_(seeds), rng_(seed) {}

  Bytes next() {
    Bytes b = seeds_[pick(seeds_.size())];
    const std::size_t rounds = 1 + pick(8);
    for (std::size_t r = 0; r < rounds; ++r)
      mutate(b);
    if (b.size() > max_input) b.resize(max_input);
    return b;
  }

private:
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

  void mutate(Bytes& b) {
    switch (pick(8)) {
    case 0: // flip one bit
      if (!b.empty()) b[pick(b.size())] ^= static_cast<std::uint8_t>(1u << pick(8));
      break;
    case 1: // a random byte
      if (!b.empty()) b[pick(b.size())] = static_cast<std::uint8_t>(pick(256));
      break;
    case 2: { // an interesting integer (either byte order) at a random offset
      static const std::uint32_t values[] = {0,      1,      0x7f,       0x80,        0xff,       0x7fff,
                                             0x8000, 0xffff, 0x7fffffff, 0x80000000u, 0xffffffffu};
      std::uint32_t v = values[pick(std::size(values))];
      const std::size_t width = std::size_t{1} << pick(3);
      if (b.size() < width) break;
      const std::size_t at = pick(b.size() - width + 1);
      const bool big = pick(2) == 1;
      for (std::size_t k = 0; k < width; ++k)
        b[at + (big ? width - 1 - k : k)] = static_cast<std::uint8_t>(v >> (8 * k));
      break;
    }
    case 3: { // insert random bytes
      const std::size_t at = pick(b.size() + 1), n = 1 + pick(16);
      Bytes run(n);
      for (auto& c : run)
        c = static_cast<std::uint8_t>(pick(256));
      b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), run.begin(), run.end());
      break;
    }
    case 4: { // delete a run
      if (b.empty()) break;
      const std::size_t at = pick(b.size()), n = 1 + pick(std::min<std::size_t>(64, b.size() - at));
      b.erase(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + n));
      break;
    }
    case 5: { // repeat a run
      if (b.empty()) break;
      const std::size_t at = pick(b.size()), n = 1 + pick(std::min<std::size_t>(64, b.size() - at));
      Bytes run(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + n));
      b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), run.begin(), run.end());
      break;
    }
    case 6: // truncate
      b.resize(pick(b.size() + 1));
      break;
    default: { // splice: the head of this input, the tail of another seed
      const Bytes& other = seeds_[pick(seeds_.size())];
      const std::size_t cut = pick(b.size() + 1), from = pick(other.size() + 1);
      b.resize(cut);
      b.insert(b.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
      break;
    }
    }
  }

  const std::vector<Bytes>& seeds_;
  std::mt19937_64 rng_;
};

void run_one(const Bytes& input, const char* last) {
  if (last)
    std::ofstream(last, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(input.data()), static_cast<std::streamsize>(input.size()));
  LLVMFuzzerTestOneInput(input.data(), input.size());
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: " << argv[0] << " SECONDS SEED_FILE_OR_DIRECTORY...\n";
    return 2;
  }
  const double seconds = std::atof(argv[1]);
  const std::vector<Bytes> seeds = load_seeds(argc, argv);
  if (seeds.empty()) {
    std::cerr << "fuzz driver: no seeds found\n";
    return 2;
  }
  const char* env_seed = std::getenv("GEOTANDEM_FUZZ_SEED");
  const std::uint64_t seed = env_seed ? std::strtoull(env_seed, nullptr, 10) : 1;
  const char* last = std::getenv("GEOTANDEM_FUZZ_LAST");

  for (const Bytes& s : seeds)
    run_one(s, last);
  Mutator mutator(seeds, seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::uint64_t runs = seeds.size();
  while (std::chrono::steady_clock::now() < end) {
    run_one(mutator.next(), last);
    ++runs;
  }
  std::cout << "fuzz driver: " << runs << " inputs (" << seeds.size() << " seeds), generator seed " << seed
            << ", no crash\n";
  return 0;
}
