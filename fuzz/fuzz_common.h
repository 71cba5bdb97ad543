// What the fuzz targets share with each other and with make_corpus, the
// seed-corpus generator: quiet protobuf logging, and the input format of
// dispatcher_fuzzer (so seeds and target agree on it).
#ifndef ANIMAT_FUZZ_FUZZ_COMMON_H_
#define ANIMAT_FUZZ_FUZZ_COMMON_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <google/protobuf/stubs/logging.h>

#include "animat/v1/genome.pb.h"

namespace animat::fuzz {

// Protobuf logs an error line for every string field with invalid UTF-8
// it parses; millions of them would drown the fuzzer's own output.
inline void QuietProtobufLogs() { google::protobuf::SetLogHandler(nullptr); }

// dispatcher_fuzzer's input: up to kMaxMessages ZeroMQ messages, one after
// the other, so that one input can reproduce what takes several steps
// (a hello, then a credit). Each message is a control byte, then its
// frames, each preceded by its length (2 bytes, little-endian, cut to what
// is left).
//
// Control bits: 0-1 the number of frames minus one (1 to 4 frames);
// 2 sent by a peer that never says hello of its own (else by the worker
// peer, which says a valid hello after every input); 3 a frame that
// decodes as a Hello gets this build's id (so seeds survive a rebuild);
// 4-5 both set: the dispatcher is polled for kWaitMs after the message
// (else it is polled without waiting).
struct FuzzMessage {
  bool stranger = false;
  bool fix_build_id = false;
  bool wait = false;
  std::vector<std::string> frames;
};

inline constexpr int kWaitMs = 2;

inline constexpr size_t kMaxMessages = 8;

inline std::vector<FuzzMessage> ParseDispatcherInput(const uint8_t* data,
                                                     size_t size) {
  std::vector<FuzzMessage> messages;
  size_t at = 0;
  while (at < size && messages.size() < kMaxMessages) {
    FuzzMessage& message = messages.emplace_back();
    const uint8_t control = data[at++];
    message.stranger = (control & 4) != 0;
    message.fix_build_id = (control & 8) != 0;
    message.wait = (control & 0x30) == 0x30;
    const int count = (control & 3) + 1;
    for (int i = 0; i < count; ++i) {
      size_t length = 0;
      if (size - at >= 2) {
        length =
            std::min<size_t>(data[at] | (data[at + 1] << 8), size - at - 2);
        at += 2;
      } else {
        at = size;
      }
      message.frames.emplace_back(reinterpret_cast<const char*>(data + at),
                                  length);
      at += length;
    }
  }
  return messages;
}

// The inverse of ParseDispatcherInput (1 to 4 frames of < 64 KiB each).
inline std::string FormatDispatcherInput(
    const std::vector<FuzzMessage>& messages) {
  std::string out;
  for (const FuzzMessage& message : messages) {
    const size_t count = std::clamp<size_t>(message.frames.size(), 1, 4);
    out.push_back(static_cast<char>((count - 1) | (message.stranger ? 4 : 0) |
                                    (message.fix_build_id ? 8 : 0) |
                                    (message.wait ? 0x30 : 0)));
    for (size_t i = 0; i < count; ++i) {
      const std::string frame =
          i < message.frames.size() ? message.frames[i] : "";
      out.push_back(static_cast<char>(frame.size() & 0xff));
      out.push_back(static_cast<char>((frame.size() >> 8) & 0xff));
      out += frame;
    }
  }
  return out;
}

// dispatcher_fuzzer keeps individuals 1..kIndividuals pending, all with
// this genome (the four-element example of docs/formats.md), so that seed
// results can name them with the right genome hash.
inline constexpr uint64_t kIndividuals = 8;

inline v1::Genome HarnessGenome() {
  v1::Genome genome;
  auto add = [&](v1::Element::Type type, double x, double y,
                 v1::Element::Channel channel) {
    v1::Element* e = genome.add_elements();
    e->set_type(type);
    e->set_sign(1);
    e->set_x(x);
    e->set_y(y);
    e->set_channel(channel);
  };
  add(v1::Element::S_IN, 2.0, 2.0, v1::Element::UNIFORM);
  add(v1::Element::P, 2.5, 2.0, v1::Element::CHANNEL_NONE);
  add(v1::Element::G_INTERNAL, 6.0, 1.0, v1::Element::CHANNEL_NONE);
  add(v1::Element::S_OUT, 6.5, 1.0, v1::Element::DIVIDE);
  return genome;
}

}  // namespace animat::fuzz

#endif  // ANIMAT_FUZZ_FUZZ_COMMON_H_
