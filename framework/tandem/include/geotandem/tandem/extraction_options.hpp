#pragma once
// The extraction's options: the one value a user sets (from a recipe's extract step, the command
// line's `geotandem extract`, or Python's geotandem.extract) and that travels unchanged to the
// collapse loop in this process and, inside the SETUP message, to every worker.
//
// Each option is declared once, in the field table of extraction_options.cpp: its name, type,
// range, unit, help and the member it sets; its default is the member initialiser below (or the
// SimplifyOptions default it names). Everything else reads that table: the ParamSpecs recipes are
// validated against (extraction_params()), the command line's options and their help, Python's
// keyword arguments, docs/recipe-schema.md and the JSON codec below.
//
// Adding an option: a member with its default here, and one row in the table of
// extraction_options.cpp. It then exists in recipes, on the command line (--name-with-dashes; a
// boolean whose default is true becomes --no-name), in Python, in the docs and in SETUP; the loop
// reads it in loop_options() (or where it is used).

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/param_fields.hpp"
#include "geotandem/core/params.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/box.hpp"

namespace geotandem::tandem {

// tandem-dump: the tandem loop, finished components dumped as they finish; tandem: kept to the end
// of the block (the seed's plain tandem); brute: extract every layer, then simplify once.
enum class ExtractMode { tandem_dump, tandem, brute };

// Which side of iso is inside a body: above (value >= iso, the default) or below (value <= iso:
// low coherence, low impedance; McOptions::below). A store's identity names the side only when it
// is below, so stores made before sides existed keep theirs.
enum class Side { above, below };

// The smallest leaf edge of the block tree, in cells (0 means one block). The block tree and the
// merges are correct down to 1 cell (leaves of 1 to 7 cells give the same component keys as one
// block on a 48^3 analytic cube), so this bound is about cost, not correctness: every leaf and
// merge has a fixed overhead, and 2-cell leaves took 25 times as long as 16-cell ones there.
inline constexpr std::int64_t min_block_size = 8;

struct ExtractionOptions {
  float iso = 0.0f;                               // isovalue: samples >= iso are inside (required)
  Side side = Side::above;                        // below: samples <= iso are inside
  double max_error = SimplifyOptions{}.max_error; // E0, voxels
  double isotropy = SimplifyOptions{}.isotropy;   // alpha
  int axis = 0;                                   // 0 = i (inline), 1 = j, 2 = k
  std::int64_t block_size = 128;                  // leaf edge of the block tree, in cells; 0: one block
  ExtractMode mode = ExtractMode::tandem_dump;    //
  bool extended_time_lag = SimplifyOptions{}.extended_time_lag;

  // Throws InvalidArgument naming the option when a value is out of its declared range, or
  // block_size is neither 0 nor at least min_block_size.
  void validate() const;
  bool operator==(const ExtractionOptions&) const = default;
};

// One option of the table: its declaration (default from ExtractionOptions{}), and how it is read
// from and written into the value (geotandem/core/param_fields.hpp).
using ExtractionField = ParamField<ExtractionOptions>;
// Every option, in the order recipes, help and docs list them.
const std::vector<ExtractionField>& extraction_fields();
// Their declarations (recipes, `geotandem plugins`, the command line, Python, the docs).
const std::vector<ParamSpec>& extraction_params();

// The value of checked parameters (every one of extraction_params(), e.g. resolve_params()'s
// result), validated. Throws InvalidArgument naming the parameter.
ExtractionOptions options_from_params(const ParamValues& values);
// The value as parameters (each of its spec's type; a choice as its word).
ParamValues to_params(const ExtractionOptions& options);
// The check parse_param cannot make alone (block_size 0 or at least min_block_size), on checked
// parameters. Throws InvalidArgument naming the parameter.
void check_params(const ParamValues& values);

// The JSON codec: every option by name, numbers as numbers (iso as the shortest decimal of its
// float: 0.6f is 0.6), booleans as booleans, choices as their word. This is the form in the SETUP
// message and in the identity a store records for a run.
nlohmann::json to_json(const ExtractionOptions& options);
// Throws InvalidArgument naming the key when one is missing, unknown, of the wrong type or out of
// range.
ExtractionOptions options_from_json(const nlohmann::json& json);

const char* to_string(ExtractMode mode);
const char* to_string(Side side);
// "above" or "below"; throws InvalidArgument otherwise.
Side parse_side(const std::string& text);
// "tandem-dump", "tandem" or "brute"; throws InvalidArgument otherwise.
ExtractMode parse_extract_mode(const std::string& text);
// "i", "j", "k" (or 0, 1, 2); throws InvalidArgument otherwise.
int parse_axis(const std::string& text);

// The loop's configuration for these options (iso, axis, E0, alpha, time lags, dumping). The
// caller sets cancel, progress and observer; brute force is `options.mode == ExtractMode::brute`.
TandemOptions loop_options(const ExtractionOptions& options);
// The leaf edge the block tree is built with for a cube of `shape` samples: block_size, or for
// block_size 0 the cube's largest edge in cells (one leaf: the whole cube as one block).
std::int64_t leaf_size(const ExtractionOptions& options, const volume::Index3& shape);

} // namespace geotandem::tandem
