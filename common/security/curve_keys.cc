#include "common/security/curve_keys.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zmq.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace animat::security {
namespace {

constexpr char kZ85Alphabet[] =
    "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&"
    "<>()[]{}@%$#";

std::string Trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

Result<std::vector<std::string>> ReadLines(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Status::IoError(path + ": " + std::strerror(errno));
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (lines.size() > 100000) {
      return Status::InvalidArgument(path + ": too many lines for a key file");
    }
    lines.push_back(line);
  }
  if (in.bad()) return Status::IoError(path + ": read failed");
  return lines;
}

// The "name = value" lines of a key file.
Result<std::map<std::string, std::string>> ReadFields(const std::string& path) {
  Result<std::vector<std::string>> lines = ReadLines(path);
  if (!lines.ok()) return lines.status();
  std::map<std::string, std::string> fields;
  for (size_t i = 0; i < lines->size(); ++i) {
    const std::string line = Trim((*lines)[i]);
    if (line.empty() || line[0] == '#') continue;
    const size_t equals = line.find('=');
    if (equals == std::string::npos) {
      return Status::InvalidArgument(path + ":" + std::to_string(i + 1) +
                                     ": expected 'name = value'");
    }
    std::string value = Trim(line.substr(equals + 1));
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
      value = value.substr(1, value.size() - 2);
    }
    fields[Trim(line.substr(0, equals))] = value;
  }
  return fields;
}

Result<std::string> KeyField(const std::map<std::string, std::string>& fields,
                             const std::string& name, const std::string& path) {
  const auto it = fields.find(name);
  if (it == fields.end()) {
    return Status::InvalidArgument(path + ": no " + name);
  }
  if (!IsZ85Key(it->second)) {
    return Status::InvalidArgument(path + ": " + name +
                                   " is not a 40-character Z85 key");
  }
  return it->second;
}

}  // namespace

bool IsZ85Key(const std::string& text) {
  return text.size() == kZ85KeyChars && Z85Decode(text).size() == kKeyBytes;
}

std::string Z85Decode(const std::string& text) {
  if (text.size() != kZ85KeyChars) return "";
  uint64_t value = 0;
  std::string bytes;
  for (size_t i = 0; i < text.size(); ++i) {
    const char* at = std::strchr(kZ85Alphabet, text[i]);
    if (at == nullptr || text[i] == '\0') return "";
    value = value * 85 + static_cast<uint64_t>(at - kZ85Alphabet);
    if (i % 5 == 4) {
      if (value > 0xffffffffu) return "";
      for (int shift = 24; shift >= 0; shift -= 8) {
        bytes.push_back(static_cast<char>((value >> shift) & 0xff));
      }
      value = 0;
    }
  }
  return bytes;
}

std::string Z85Encode(const std::string& bytes) {
  if (bytes.size() != kKeyBytes) return "";
  std::string text;
  for (size_t i = 0; i < bytes.size(); i += 4) {
    uint32_t value = 0;
    for (size_t j = 0; j < 4; ++j) {
      value = (value << 8) | static_cast<uint8_t>(bytes[i + j]);
    }
    char chunk[5];
    for (int j = 4; j >= 0; --j) {
      chunk[j] = kZ85Alphabet[value % 85];
      value /= 85;
    }
    text.append(chunk, 5);
  }
  return text;
}

Result<CurveKeyPair> GenerateKeyPair() {
  if (!zmq_has("curve")) {
    return Status::Internal("this libzmq was built without CurveZMQ");
  }
  char public_key[41];
  char secret_key[41];
  if (zmq_curve_keypair(public_key, secret_key) != 0) {
    return Status::Internal(std::string("zmq_curve_keypair: ") +
                            zmq_strerror(zmq_errno()));
  }
  return CurveKeyPair{public_key, secret_key};
}

Status WriteKeyPair(const std::string& stem, const CurveKeyPair& pair,
                    const std::string& comment) {
  if (!IsZ85Key(pair.public_key) || !IsZ85Key(pair.secret_key)) {
    return Status::InvalidArgument("not a Z85 key pair");
  }
  const std::string key_path = stem + ".key";
  const std::string pub_path = stem + ".pub";
  for (const std::string& path : {key_path, pub_path}) {
    if (access(path.c_str(), F_OK) == 0) {
      return Status::InvalidArgument(path +
                                     " exists; keys are never overwritten");
    }
  }
  const std::string header = "# " + comment + "\n";
  const std::string secret = header +
                             "# Secret: keep this file private.\n"
                             "public-key = \"" +
                             pair.public_key +
                             "\"\n"
                             "secret-key = \"" +
                             pair.secret_key + "\"\n";
  const int fd =
      open(key_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return Status::IoError(key_path + ": " + std::strerror(errno));
  const ssize_t written = write(fd, secret.data(), secret.size());
  const bool ok = written == static_cast<ssize_t>(secret.size());
  if (close(fd) != 0 || !ok) {
    return Status::IoError(key_path + ": write failed");
  }
  std::ofstream pub(pub_path);
  pub << header << "public-key = \"" << pair.public_key << "\"\n";
  pub.close();
  if (!pub) return Status::IoError(pub_path + ": write failed");
  return Status::Ok();
}

Result<CurveKeyPair> ReadKeyPair(const std::string& path) {
  Result<std::map<std::string, std::string>> fields = ReadFields(path);
  if (!fields.ok()) return fields.status();
  Result<std::string> public_key = KeyField(*fields, "public-key", path);
  if (!public_key.ok()) return public_key.status();
  Result<std::string> secret_key = KeyField(*fields, "secret-key", path);
  if (!secret_key.ok()) return secret_key.status();
  char derived[41];
  if (zmq_curve_public(derived, secret_key->c_str()) != 0 ||
      *public_key != derived) {
    return Status::InvalidArgument(
        path + ": the public key does not belong to the secret key");
  }
  return CurveKeyPair{*public_key, *secret_key};
}

Result<std::string> ReadPublicKey(const std::string& path) {
  Result<std::map<std::string, std::string>> fields = ReadFields(path);
  if (!fields.ok()) return fields.status();
  return KeyField(*fields, "public-key", path);
}

Result<std::map<std::string, std::string>> ReadAllowList(
    const std::string& path) {
  Result<std::vector<std::string>> lines = ReadLines(path);
  if (!lines.ok()) return lines.status();
  std::map<std::string, std::string> allowed;
  for (size_t i = 0; i < lines->size(); ++i) {
    const std::string line = Trim((*lines)[i]);
    if (line.empty() || line[0] == '#') continue;
    const size_t space = line.find_first_of(" \t");
    const std::string key = line.substr(0, space);
    if (!IsZ85Key(key)) {
      return Status::InvalidArgument(
          path + ":" + std::to_string(i + 1) +
          ": expected a 40-character Z85 public key, then an optional name");
    }
    const std::string name =
        space == std::string::npos ? key : Trim(line.substr(space));
    allowed[key] = name;
  }
  if (allowed.empty()) {
    return Status::InvalidArgument(path +
                                   ": no keys (it would refuse every worker)");
  }
  return allowed;
}

bool IsLocalEndpoint(const std::string& endpoint) {
  if (endpoint.rfind("inproc://", 0) == 0 || endpoint.rfind("ipc://", 0) == 0) {
    return true;
  }
  if (endpoint.rfind("tcp://", 0) != 0) return false;
  std::string host = endpoint.substr(6);
  // tcp://source;host:port names a source address first.
  if (const size_t semicolon = host.find(';'); semicolon != std::string::npos) {
    host = host.substr(semicolon + 1);
  }
  if (!host.empty() && host[0] == '[') {
    const size_t close = host.find(']');
    return close != std::string::npos && host.substr(1, close - 1) == "::1";
  }
  host = host.substr(0, host.rfind(':'));
  if (host == "localhost") return true;
  // 127.a.b.c with numeric parts only.
  if (host.rfind("127.", 0) != 0) return false;
  int dots = 0;
  for (char c : host) {
    if (c == '.') {
      ++dots;
    } else if (c < '0' || c > '9') {
      return false;
    }
  }
  return dots == 3;
}

}  // namespace animat::security
