// The endpoints the master binds and workers connect to (--bind,
// --connect): "tcp://HOST:PORT" or "ipc://PATH" (docs/protocol.md),
// checked before ZeroMQ sees them, so that a mistyped endpoint gets a
// message saying what was expected instead of an exception.
// Thread-safe (pure).
#ifndef ANIMAT_COMMON_PROTOCOL_ENDPOINT_H_
#define ANIMAT_COMMON_PROTOCOL_ENDPOINT_H_

#include <string_view>

#include "common/base/status.h"

namespace animat::protocol {

enum class EndpointUse {
  kBind,     // The master: HOST and PORT may also be "*" (every interface;
             // any free port).
  kConnect,  // A worker.
};

// OK for "tcp://HOST:PORT" (HOST a name, an IPv4 address or an [IPv6]
// address; PORT 1 to 65535) and "ipc://PATH" (PATH of 1 to 107 bytes, the
// limit of a Unix socket's name); kInvalidArgument otherwise, quoting the
// endpoint and saying what is wrong and what was expected.
Status CheckEndpoint(std::string_view endpoint, EndpointUse use);

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_ENDPOINT_H_
