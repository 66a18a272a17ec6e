#pragma once
// CurveZMQ for the manager/worker sockets when the manager listens on anything but loopback.
//
// The manager makes fresh keys for every run: its own pair and one pair for its workers. They are
// written to DIR/run-keys/ (the directory 0700, each file 0600: readable by the user alone), the
// worker's file path is exported as GEOTANDEM_CURVE_KEY_FILE so that workers started from this
// process (locally or as scheduler jobs, which inherit the environment) find it, and a ZAP handler
// admits only the workers' public key; every refusal is logged with the peer's address. On
// loopback nothing changes (plain TCP: only this machine's users can connect, and they can read
// the store anyway).
#include <memory>
#include <string>

#include <zmq.hpp>

#include "geotandem/core/log.hpp"

namespace geotandem::runtime::detail {

// The variable that carries the worker's key file to the workers.
inline constexpr const char* curve_key_variable = "GEOTANDEM_CURVE_KEY_FILE";

class ServerSecurity; // the ZAP handler's thread and the key files; ends the handler when destroyed

// True for tcp://127.x.x.x:..., tcp://localhost:..., tcp://[::1]:... and non-TCP transports.
bool is_loopback_endpoint(const std::string& endpoint);

// Call before `router.bind(bind)`. For a non-loopback `bind`: makes the keys in `key_dir`, starts
// the ZAP handler in `context` and makes `router` a CURVE server; returns the object that keeps
// them (keep it until the socket is closed). For loopback: returns null and changes nothing.
// Throws IoError when the keys cannot be written.
std::shared_ptr<ServerSecurity> secure_manager_socket(zmq::context_t& context, zmq::socket_t& router,
                                                      const std::string& bind, const std::string& key_dir, Logger& log);

// Throws IoError (naming the file) when GEOTANDEM_CURVE_KEY_FILE is set but cannot be read or
// holds no valid keys. The worker calls it before its I/O thread starts.
void check_worker_keys();

// Call before `dealer.connect(...)`. When GEOTANDEM_CURVE_KEY_FILE is set, makes `dealer` a CURVE
// client with the keys in that file; otherwise changes nothing.
void secure_worker_socket(zmq::socket_t& dealer) noexcept;

} // namespace geotandem::runtime::detail
