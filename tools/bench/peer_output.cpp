#include "tools/bench/peer_output.h"

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>

namespace metrosync::bench {

namespace {

using nlohmann::json;

std::string lastLine(const std::string& text) {
  size_t end = text.find_last_not_of(" \t\r\n");
  if (end == std::string::npos) return "";
  const size_t begin = text.rfind('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end + 1 - (begin + 1));
}

const json& key(const json& j, const char* name) {
  if (!j.contains(name)) throw std::invalid_argument(std::string("no key '") + name + "'");
  return j.at(name);
}

double number(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_number()) throw std::invalid_argument(std::string("'") + name + "' is not a number");
  return v.get<double>();
}

long integer(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_number_integer())
    throw std::invalid_argument(std::string("'") + name + "' is not an integer");
  return v.get<long>();
}

template <class T>
std::vector<T> list(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_array()) throw std::invalid_argument(std::string("'") + name + "' is not a list");
  std::vector<T> out;
  for (const json& x : v) {
    if (!x.is_number() || (std::is_integral_v<T> && !x.is_number_integer()))
      throw std::invalid_argument(std::string("'") + name + "' holds a non-number");
    out.push_back(x.get<T>());
  }
  return out;
}

std::string text(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_string()) throw std::invalid_argument(std::string("'") + name + "' is not a string");
  return v.get<std::string>();
}

PeerOutput fromJson(const json& j) {
  PeerOutput p;
  p.n = static_cast<int>(integer(j, "N"));
  p.method = text(j, "method");
  p.rtol = number(j, "rtol");
  p.atol = number(j, "atol");
  p.t = number(j, "t");
  p.state = list<double>(j, "state");
  p.mode = text(j, "mode");
  p.wall_ms = number(j, "wall_ms");
  p.cpu_ms = number(j, "cpu_ms");
  p.wall_ms_runs = list<double>(j, "wall_ms_runs");
  p.steps = integer(j, "steps");
  p.rhs_calls = integer(j, "rhs_calls");
  p.events = integer(j, "events");
  p.restarts = integer(j, "restarts");
  p.kicks = list<long>(j, "kicks");
  p.platform_events = integer(j, "platform_events");
  p.stick_to_slip = integer(j, "stick_to_slip");
  p.slip_stops = integer(j, "slip_stops");
  p.stick_time = number(j, "stick_time");
  return p;
}

}  // namespace

PeerOutput parsePeerOutput(const std::string& out) {
  const std::string line = lastLine(out);
  if (line.empty()) throw std::invalid_argument("the peer printed nothing");
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception& e) {
    throw std::invalid_argument("the peer's last line is not JSON (" + std::string(e.what()) +
                                "): " + line.substr(0, 200));
  }
  if (!j.is_object()) throw std::invalid_argument("the peer's last line is not a JSON object");
  PeerOutput p;
  try {
    p = fromJson(j);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("the peer's JSON: ") + e.what());
  }
  if (p.n < 1) throw std::invalid_argument("the peer's JSON: N = " + std::to_string(p.n));
  if (p.state.size() != static_cast<size_t>(2 * p.n + 2))
    throw std::invalid_argument("the peer's JSON: 'state' has " + std::to_string(p.state.size()) +
                                " values, not 2N + 2 = " + std::to_string(2 * p.n + 2));
  if (p.kicks.size() != static_cast<size_t>(p.n))
    throw std::invalid_argument("the peer's JSON: 'kicks' has " + std::to_string(p.kicks.size()) +
                                " values, not N = " + std::to_string(p.n));
  return p;
}

}  // namespace metrosync::bench
