// CurveZMQ keys for the master–worker link (docs/security.md): key pairs,
// the files that hold them, allow-lists of worker keys, and which
// endpoints stay on this machine.
//
// Keys travel as Z85 text (40 characters for 32 bytes). A key pair file
// ("NAME.key", mode 0600) holds both halves; a public key file
// ("NAME.pub") only the public one; an allow-list holds one public key per
// line, each optionally followed by a name. Readers take files from users:
// anything malformed is a Status naming the file and line, never a crash.
// All functions are thread-safe.
#ifndef ANIMAT_COMMON_SECURITY_CURVE_KEYS_H_
#define ANIMAT_COMMON_SECURITY_CURVE_KEYS_H_

#include <map>
#include <string>

#include "common/base/status.h"

namespace animat::security {

inline constexpr size_t kKeyBytes = 32;
inline constexpr size_t kZ85KeyChars = 40;

struct CurveKeyPair {
  std::string public_key;  // Z85, 40 characters.
  std::string secret_key;  // Z85, 40 characters. Keep it private.
};

// True for 40 characters of the Z85 alphabet that decode to 32 bytes.
bool IsZ85Key(const std::string& text);
// The 32 bytes of a Z85 key; empty if `text` is not one.
std::string Z85Decode(const std::string& text);
// The Z85 text of 32 bytes; empty if `bytes` is not 32 bytes long.
std::string Z85Encode(const std::string& bytes);

// A fresh key pair from libzmq (libsodium's randomness). Fails when libzmq
// was built without CurveZMQ.
Result<CurveKeyPair> GenerateKeyPair();

// Writes "<stem>.key" (both halves, created with mode 0600; an existing
// file is refused, never overwritten) and "<stem>.pub" (the public half).
Status WriteKeyPair(const std::string& stem, const CurveKeyPair& pair,
                    const std::string& comment);

// Reads a key pair file (both halves, checked to belong together).
Result<CurveKeyPair> ReadKeyPair(const std::string& path);
// Reads the public key of a public key file or of a key pair file.
Result<std::string> ReadPublicKey(const std::string& path);

// Reads an allow-list: lines "KEY [name]", '#' comments and blank lines
// ignored. Returns Z85 key -> name (the key itself when unnamed). An empty
// list is an error: it would refuse every worker.
Result<std::map<std::string, std::string>> ReadAllowList(
    const std::string& path);

// True for endpoints reachable from this machine only: inproc://, ipc://,
// and tcp:// on 127.0.0.0/8, ::1 or "localhost". Everything else
// (tcp://*:N, tcp://0.0.0.0:N, a host name, an interface) listens beyond
// it.
bool IsLocalEndpoint(const std::string& endpoint);

}  // namespace animat::security

#endif  // ANIMAT_COMMON_SECURITY_CURVE_KEYS_H_
