#include "common/protocol/endpoint.h"

#include <algorithm>
#include <string>

#include "common/base/text.h"

namespace animat::protocol {
namespace {

constexpr size_t kMaxIpcPath = 107;  // sizeof(sockaddr_un::sun_path) - 1.

bool IsNameCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
         (c >= '0' && c <= '9') || c == '-' || c == '.' || c == '_';
}

// What is wrong with HOST (empty when nothing).
std::string HostProblem(std::string_view host, EndpointUse use) {
  if (host.empty()) return "no host";
  if (host == "*") {
    return use == EndpointUse::kBind ? "" : "a worker cannot connect to *";
  }
  if (host.front() == '[') {
    const bool ipv6 = host.size() > 2 && host.back() == ']' &&
                      std::all_of(host.begin() + 1, host.end() - 1, [](char c) {
                        return (c >= '0' && c <= '9') ||
                               (c >= 'a' && c <= 'f') ||
                               (c >= 'A' && c <= 'F') || c == ':' || c == '.';
                      });
    return ipv6 ? "" : "a malformed [IPv6] address";
  }
  if (!std::all_of(host.begin(), host.end(), IsNameCharacter)) {
    std::string problem = "the host \"";
    problem += Excerpt(host, 60);
    problem += "\" is no name or address";
    return problem;
  }
  return "";
}

// What is wrong with PORT (empty when nothing).
std::string PortProblem(std::string_view port, EndpointUse use) {
  if (port == "*") {
    return use == EndpointUse::kBind ? "" : "a worker needs a port number";
  }
  if (port.empty() || port.size() > 5 ||
      !std::all_of(port.begin(), port.end(),
                   [](char c) { return c >= '0' && c <= '9'; })) {
    std::string problem = "the port \"";
    problem += Excerpt(port, 20);
    problem += "\" is not a number";
    return problem;
  }
  const int number = std::stoi(std::string(port));
  if (number < 1 || number > 65535) {
    std::string problem = "the port ";
    problem += port;
    problem += " is not from 1 to 65535";
    return problem;
  }
  return "";
}

std::string Problem(std::string_view endpoint, EndpointUse use) {
  constexpr std::string_view kTcp = "tcp://";
  constexpr std::string_view kIpc = "ipc://";
  if (endpoint.substr(0, kIpc.size()) == kIpc) {
    const std::string_view path = endpoint.substr(kIpc.size());
    if (path.empty()) return "no path";
    if (path.size() > kMaxIpcPath) {
      return "the path is longer than " + std::to_string(kMaxIpcPath) +
             " bytes";
    }
    return "";
  }
  if (endpoint.substr(0, kTcp.size()) != kTcp) {
    return "neither tcp:// nor ipc://";
  }
  const std::string_view rest = endpoint.substr(kTcp.size());
  const size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos || rest.back() == ']') {
    return "no port";
  }
  std::string problem = HostProblem(rest.substr(0, colon), use);
  if (problem.empty()) problem = PortProblem(rest.substr(colon + 1), use);
  return problem;
}

}  // namespace

Status CheckEndpoint(std::string_view endpoint, EndpointUse use) {
  const std::string problem = Problem(endpoint, use);
  if (problem.empty()) return Status::Ok();
  std::string message = "\"";
  message += Excerpt(endpoint, 120);
  message += "\": ";
  message += problem;
  message += "; expected tcp://HOST:PORT";
  if (use == EndpointUse::kBind) message += " (HOST or PORT may be *)";
  message += " or ipc://PATH, e.g. tcp://127.0.0.1:5555";
  return Status::InvalidArgument(std::move(message));
}

}  // namespace animat::protocol
