// zmq_poll that a signal does not abort: an interrupted wait reports no
// events (the caller's loop then sees whatever the signal handler set).
#ifndef ANIMAT_COMMON_PROTOCOL_ZMQ_POLL_H_
#define ANIMAT_COMMON_PROTOCOL_ZMQ_POLL_H_

#include <cerrno>
#include <chrono>
#include <zmq.hpp>

namespace animat::protocol {

// Returns the number of items with events, 0 on timeout or interruption.
inline int Poll(zmq::pollitem_t* items, int count,
                std::chrono::milliseconds timeout) {
  try {
    return zmq::poll(items, count, timeout);
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;
    for (int i = 0; i < count; ++i) items[i].revents = 0;
    return 0;
  }
}

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_ZMQ_POLL_H_
