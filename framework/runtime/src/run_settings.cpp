// RunSettings as the JSON text of a SETUP message (run_settings.hpp).
#include "geotandem/runtime/run_settings.hpp"

#include <nlohmann/json.hpp>

#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime {

std::string RunSettings::to_json() const {
  const nlohmann::json j = {{"version", kProtocolVersion},
                            {"volume", volume},
                            {"store", store},
                            {"extraction", tandem::to_json(extraction)},
                            {"run", run},
                            {"chunk_bytes", chunk_bytes}};
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
    s.extraction = tandem::options_from_json(j.at("extraction"));
    s.run = j.at("run").get<std::int64_t>();
    s.chunk_bytes = j.at("chunk_bytes").get<std::uint64_t>();
    if (s.chunk_bytes == 0 || s.chunk_bytes > (std::uint64_t{1} << 28))
      throw ProtocolError("run settings: chunk_bytes " + std::to_string(s.chunk_bytes) + " is not in 1..2^28");
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("run settings: ") + e.what());
  } catch (const InvalidArgument& e) {
    throw ProtocolError("run settings: " + e.message());
  }
}

} // namespace geotandem::runtime
