#pragma once
// The world main() builds and hands to every subcommand: logger, progress reporter, cancel token.
// Each subcommand lives in its own cmd_<name>.cpp and is added by an explicit call in main.cpp.

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::app {

struct Context {
  Logger& log;
  CancelToken cancel;
  bool quiet = false;
  // The log level in effect (--log-level, or warning under -q), handed on to the workers.
  std::string log_level = "info";
  // A fresh progress reporter on stderr (a bar on a terminal, plain lines otherwise).
  std::unique_ptr<Progress> progress() const { return make_stderr_progress(quiet); }
};

// A subcommand sets `run` on itself; main calls the one the user chose. It returns the exit code
// and throws geotandem::Error for failures (main prints them and maps them to exit codes).
using Runner = std::function<int()>;

void add_synth_command(CLI::App& app, Context& context, Runner& run);
void add_info_command(CLI::App& app, Context& context, Runner& run);
void add_extract_command(CLI::App& app, Context& context, Runner& run);
void add_store_command(CLI::App& app, Context& context, Runner& run);
// cmd_store_labels.cpp: `store labels`, added by add_store_command.
void add_store_labels(CLI::App* parent, Context& context, Runner& run);
void add_plugins_command(CLI::App& app, Context& context, Runner& run);
void add_validate_command(CLI::App& app, Context& context, Runner& run);
void add_workflow_command(CLI::App& app, Context& context, Runner& run);
void add_worker_command(CLI::App& app, Context& context, Runner& run);

// Checks on numeric options that CLI11 (2.1) would otherwise take in silently: a negative number
// given to an unsigned option wraps around to a huge one (`--workers -1` asked for 2^64 - 1 local
// workers), and NaN passes every comparison after it.
// A count or a seed: no sign.
const CLI::Validator& not_negative();
// A real number that is not NaN (infinities pass: a bound that is not there).
const CLI::Validator& not_nan();
// A real number > 0, not NaN (infinity passes).
const CLI::Validator& positive();
// The value of a --no-data option as a float sample's value; throws InvalidArgument when it is not a
// finite number within float range.
std::optional<float> no_data_option(const std::optional<double>& value);
// The options that say which cube of a file to read and how: --variable (multidimensional files)
// and --inline-byte / --crossline-byte (SEG-Y), shared by the commands that open a cube.
void add_cube_reading_options(CLI::App& cmd, std::string& variable, volume::SegyOptions& segy);
// --crs: the CRS of the cube's map coordinates (an EPSG code or a WKT), replacing the file's.
void add_crs_option(CLI::App& cmd, std::string& crs);
// The CRS of a --crs option checked through OSR (volume::parse_crs); nullopt when not given.
// Throws InvalidArgument naming the option.
std::optional<volume::Crs> crs_option(const std::string& text);

// cmd_worker.cpp: how workers rebuild the input volume. The description of a cube file (JSON
// text), and the volume a description names (the runtime's VolumeFactory).
// `hint`: what opening the file found, for the workers (volume::Volume::reopen_hint).
// `fill_highest`: filled missing samples are the highest float (an extraction of the side below).
std::string describe_cube_file(const std::string& path, const std::string& nan, std::optional<float> no_data,
                               const std::string& variable, const volume::SegyOptions& segy, const std::string& crs,
                               const std::string& hint = {}, bool fill_highest = false);
std::shared_ptr<const volume::Volume> open_described_volume(const std::string& description, Logger& log);
// This executable's path, for the command line of local workers.
std::string self_executable();
// The command line of a worker: this executable at the manager's log level (so that -q quiets the
// workers' info lines too).
std::vector<std::string> worker_command(const Context& context);

} // namespace geotandem::app
