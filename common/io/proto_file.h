// Reading and writing protobuf messages as files, the format chosen by the
// file name's extension:
//   .json                          proto JSON (field names as in .proto or
//                                  lowerCamelCase; enums by name)
//   .txtpb, .textproto, .pbtxt     proto text format
//   .binpb, .pb                    binary wire format
// Thread-safe (no shared state).
#ifndef ANIMAT_COMMON_IO_PROTO_FILE_H_
#define ANIMAT_COMMON_IO_PROTO_FILE_H_

#include <string>

#include <google/protobuf/message.h>

#include "common/base/status.h"

namespace animat {

enum class ProtoFormat { kJson, kText, kBinary };

// The format for `path`, or kInvalidArgument naming the accepted
// extensions.
Result<ProtoFormat> ProtoFormatForPath(const std::string& path);

// Parses `text` in `format` into `message` (cleared first). Errors say what
// is wrong and where (line and column, or the field) without a file name.
Status ParseProto(const std::string& text, ProtoFormat format,
                  google::protobuf::Message* message);

// Reads the file into `message`. Errors start with the path:
// "genome.json: elements[0].sign: ...", "cfg.txtpb:3:7: ...".
Status ReadProtoFile(const std::string& path,
                     google::protobuf::Message* message);

// Serialises `message` in `format`. JSON output prints every field,
// including those at their default value, with names as in the .proto.
std::string SerializeProto(const google::protobuf::Message& message,
                           ProtoFormat format);

// Writes `message` to `path` in the format of its extension; "-" writes
// JSON to standard output.
Status WriteProtoFile(const std::string& path,
                      const google::protobuf::Message& message);

// Reads a whole file. kNotFound or kIoError name the path.
Result<std::string> ReadFile(const std::string& path);
// Writes (replaces) a whole file; "-" is standard output.
Status WriteFile(const std::string& path, const std::string& contents);

}  // namespace animat

#endif  // ANIMAT_COMMON_IO_PROTO_FILE_H_
