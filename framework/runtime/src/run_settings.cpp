// RunSettings as the JSON text of a SETUP message (run_settings.hpp).
#include "geotandem/runtime/run_settings.hpp"

#include <nlohmann/json.hpp>

#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime {

std::string RunSettings::to_json() const {
  nlohmann::json j = {{"version", kProtocolVersion},
                      {"volume", volume},
                      {"store", store},
                      {"block_size", block_size},
                      {"iso", iso},
                      {"axis", axis},
                      {"max_error", max_error},
                      {"isotropy", isotropy},
                      {"extended_time_lag", extended_time_lag},
                      {"dump", dump},
                      {"brute", brute},
                      {"run", run},
                      {"chunk_bytes", chunk_bytes}};
  if (below) j["side"] = "below";
  return j.dump();
}

RunSettings RunSettings::from_json(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    if (j.at("version").get<int>() != kProtocolVersion)
      throw ProtocolError("run settings of protocol version " + j.at("version").dump());
    RunSettings s;
    s.volume = j.at("volume").get<std::string>();
    s.store = j.at("store").get<std::string>();
    s.block_size = j.at("block_size").get<std::int64_t>();
    s.iso = j.at("iso").get<float>();
    if (j.contains("side")) {
      const auto side = j.at("side").get<std::string>();
      if (side != "above" && side != "below") throw ProtocolError("run settings: side '" + side + "'");
      s.below = side == "below";
    }
    s.axis = j.at("axis").get<int>();
    s.max_error = j.at("max_error").get<double>();
    s.isotropy = j.at("isotropy").get<double>();
    s.extended_time_lag = j.at("extended_time_lag").get<bool>();
    s.dump = j.at("dump").get<bool>();
    s.brute = j.at("brute").get<bool>();
    s.run = j.at("run").get<std::int64_t>();
    s.chunk_bytes = j.at("chunk_bytes").get<std::uint64_t>();
    if (s.chunk_bytes == 0 || s.chunk_bytes > (std::uint64_t{1} << 28))
      throw ProtocolError("run settings: chunk_bytes " + std::to_string(s.chunk_bytes) + " is not in 1..2^28");
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("run settings: ") + e.what());
  }
}

tandem::TandemOptions RunSettings::tandem_options() const {
  tandem::TandemOptions o;
  o.iso = iso;
  o.below = below;
  o.axis = axis;
  o.simplify.max_error = max_error;
  o.simplify.isotropy = isotropy;
  o.simplify.extended_time_lag = extended_time_lag;
  o.dump = dump;
  return o;
}

} // namespace geotandem::runtime
