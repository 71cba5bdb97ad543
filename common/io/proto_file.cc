#include "common/io/proto_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>
#include <google/protobuf/util/json_util.h>

#include "common/base/text.h"

namespace animat {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Collects text-format parse errors as "line:column: message".
class TextErrors : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (!text_.empty()) text_ += "; ";
    text_ += std::to_string(line + 1) + ":" + std::to_string(column + 1) +
             ": " + message;
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

// The JSON parser's "what\ncontext\n   ^" as one line, "what, at
// \"text from the caret\"", escaped (the input may be any bytes).
std::string JsonError(const std::string& message) {
  const size_t first = message.find('\n');
  const size_t second =
      first == std::string::npos ? first : message.find('\n', first + 1);
  if (second == std::string::npos) return ForeignText(message);
  std::string what = message.substr(0, first);
  if (!what.empty() && what.back() == '.') what.pop_back();
  const std::string context = message.substr(first + 1, second - first - 1);
  const std::string caret = message.substr(second + 1);
  const size_t column = caret.find('^');
  if (column == std::string::npos || caret.find_first_not_of(' ') != column ||
      column > context.size()) {
    return ForeignText(message);
  }
  if (column == context.size()) return ForeignText(what);
  return ForeignText(what) + " at \"" + Excerpt(context.substr(column), 40) +
         "\"";
}

}  // namespace

Result<ProtoFormat> ProtoFormatForPath(const std::string& path) {
  if (EndsWith(path, ".json")) return ProtoFormat::kJson;
  if (EndsWith(path, ".txtpb") || EndsWith(path, ".textproto") ||
      EndsWith(path, ".pbtxt")) {
    return ProtoFormat::kText;
  }
  if (EndsWith(path, ".binpb") || EndsWith(path, ".pb")) {
    return ProtoFormat::kBinary;
  }
  return Status::InvalidArgument(
      path +
      ": unknown file type; use .json, .txtpb (or .textproto, .pbtxt) "
      "or .binpb");
}

Status ParseProto(const std::string& text, ProtoFormat format,
                  google::protobuf::Message* message) {
  message->Clear();
  switch (format) {
    case ProtoFormat::kJson: {
      google::protobuf::util::JsonParseOptions options;
      options.ignore_unknown_fields = false;
      const auto status =
          google::protobuf::util::JsonStringToMessage(text, message, options);
      if (!status.ok()) {
        return Status::InvalidArgument(
            JsonError(std::string(status.message())));
      }
      return Status::Ok();
    }
    case ProtoFormat::kText: {
      google::protobuf::TextFormat::Parser parser;
      TextErrors errors;
      parser.RecordErrorsTo(&errors);
      if (!parser.ParseFromString(text, message)) {
        return Status::InvalidArgument(errors.text().empty()
                                           ? "malformed text format"
                                           : ForeignText(errors.text()));
      }
      return Status::Ok();
    }
    case ProtoFormat::kBinary:
      if (!message->ParseFromString(text)) {
        return Status::InvalidArgument("malformed binary " +
                                       message->GetTypeName());
      }
      return Status::Ok();
  }
  return Status::Internal("unknown format");
}

Status ReadProtoFile(const std::string& path,
                     google::protobuf::Message* message) {
  Result<ProtoFormat> format = ProtoFormatForPath(path);
  if (!format.ok()) return format.status();
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  Status status = ParseProto(*text, *format, message);
  if (!status.ok()) {
    // Text-format errors start with "line:column", which reads best glued
    // to the path.
    const bool located =
        *format == ProtoFormat::kText && !status.message().empty() &&
        std::isdigit(static_cast<unsigned char>(status.message()[0]));
    return Status::InvalidArgument(path + (located ? ":" : ": ") +
                                   status.message());
  }
  return Status::Ok();
}

std::string SerializeProto(const google::protobuf::Message& message,
                           ProtoFormat format) {
  std::string out;
  switch (format) {
    case ProtoFormat::kJson: {
      google::protobuf::util::JsonPrintOptions options;
      options.add_whitespace = true;
      options.always_print_primitive_fields = true;
      options.preserve_proto_field_names = true;
      (void)google::protobuf::util::MessageToJsonString(message, &out, options);
      break;
    }
    case ProtoFormat::kText:
      google::protobuf::TextFormat::PrintToString(message, &out);
      break;
    case ProtoFormat::kBinary:
      message.SerializeToString(&out);
      break;
  }
  return out;
}

Status WriteProtoFile(const std::string& path,
                      const google::protobuf::Message& message) {
  if (path == "-") {
    return WriteFile(path, SerializeProto(message, ProtoFormat::kJson));
  }
  Result<ProtoFormat> format = ProtoFormatForPath(path);
  if (!format.ok()) return format.status();
  return WriteFile(path, SerializeProto(message, *format));
}

Result<std::string> ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    if (err == ENOENT) return Status::NotFound(path + ": no such file");
    return Status::IoError(path + ": " + std::strerror(err));
  }
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) return Status::IoError(path + ": read failed");
  return contents.str();
}

Status WriteFile(const std::string& path, const std::string& contents) {
  if (path == "-") {
    std::cout << contents;
    std::cout.flush();
    return std::cout ? Status::Ok() : Status::IoError("stdout: write failed");
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Status::IoError(path + ": " + std::strerror(errno));
  out << contents;
  out.close();
  if (!out) return Status::IoError(path + ": write failed");
  return Status::Ok();
}

}  // namespace animat
