// CurveZMQ keys, key files, allow-lists and local endpoints
// (common/security/curve_keys.h).
#include "common/security/curve_keys.h"

#include <sys/stat.h>
#include <unistd.h>
#include <zmq.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace animat::security {
namespace {

// The key pair of libzmq's own tests (tests/testutil_security.cpp).
constexpr char kPublic[] = "Yne@$w-vo<fVvi]a<NY6T1ed:M$fCG*[IaLV{hID";
constexpr char kSecret[] = "D:)Q[IlAW!ahhC2ac:9*A}h:p?([4%wOTJ%JR%cs";

class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/animat-keys-test.XXXXXX";
    path_ = mkdtemp(pattern);
  }
  ~TempDir() { std::system(("rm -rf '" + path_ + "'").c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Z85Test, AgreesWithLibzmqBothWays) {
  uint8_t bytes[32];
  ASSERT_NE(zmq_z85_decode(bytes, kPublic), nullptr);
  const std::string decoded = Z85Decode(kPublic);
  ASSERT_EQ(decoded.size(), 32u);
  EXPECT_EQ(decoded, std::string(reinterpret_cast<char*>(bytes), 32));
  EXPECT_EQ(Z85Encode(decoded), kPublic);
  char text[41];
  for (int seed = 0; seed < 50; ++seed) {
    std::string random(32, '\0');
    for (int i = 0; i < 32; ++i) {
      random[i] = static_cast<char>((seed * 131 + i * 71 + i * i) & 0xff);
    }
    ASSERT_NE(
        zmq_z85_encode(text, reinterpret_cast<uint8_t*>(random.data()), 32),
        nullptr);
    EXPECT_EQ(Z85Encode(random), text);
    EXPECT_EQ(Z85Decode(text), random);
  }
}

TEST(Z85Test, RejectsWhatIsNotAKey) {
  EXPECT_TRUE(IsZ85Key(kPublic));
  EXPECT_FALSE(IsZ85Key(""));
  EXPECT_FALSE(IsZ85Key(std::string(kPublic).substr(1)));  // 39 characters.
  EXPECT_FALSE(IsZ85Key(std::string(kPublic) + "0"));      // 41.
  EXPECT_FALSE(IsZ85Key(std::string(39, '0') + " "));      // Not Z85.
  EXPECT_FALSE(IsZ85Key(std::string(39, '0') + "\""));     // Not Z85.
  EXPECT_FALSE(IsZ85Key(std::string(40, '#')));            // Above 2^32.
  EXPECT_EQ(Z85Encode("short"), "");
}

TEST(KeyFileTest, WrittenPairReadsBackWithSecretFilePrivate) {
  TempDir dir;
  Result<CurveKeyPair> pair = GenerateKeyPair();
  ASSERT_TRUE(pair.ok()) << pair.status().ToString();
  EXPECT_TRUE(IsZ85Key(pair->public_key));
  EXPECT_TRUE(IsZ85Key(pair->secret_key));
  const std::string stem = dir.path() + "/master";
  ASSERT_TRUE(WriteKeyPair(stem, *pair, "test").ok());

  struct stat info;
  ASSERT_EQ(stat((stem + ".key").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  Result<CurveKeyPair> read = ReadKeyPair(stem + ".key");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->public_key, pair->public_key);
  EXPECT_EQ(read->secret_key, pair->secret_key);
  Result<std::string> pub = ReadPublicKey(stem + ".pub");
  ASSERT_TRUE(pub.ok());
  EXPECT_EQ(*pub, pair->public_key);
  std::ifstream pub_file(stem + ".pub");
  const std::string pub_text((std::istreambuf_iterator<char>(pub_file)), {});
  EXPECT_FALSE(Contains(pub_text, pair->secret_key));
  EXPECT_FALSE(ReadKeyPair(stem + ".pub").ok());  // No secret half.
}

TEST(KeyFileTest, ExistingKeysAreNeverOverwritten) {
  TempDir dir;
  const std::string stem = dir.path() + "/worker";
  ASSERT_TRUE(WriteKeyPair(stem, {kPublic, kSecret}, "first").ok());
  Result<CurveKeyPair> other = GenerateKeyPair();
  ASSERT_TRUE(other.ok());
  const Status again = WriteKeyPair(stem, *other, "second");
  ASSERT_FALSE(again.ok());
  EXPECT_TRUE(Contains(again.message(), "never overwritten"));
  Result<CurveKeyPair> read = ReadKeyPair(stem + ".key");
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read->secret_key, kSecret);
}

TEST(KeyFileTest, MalformedFilesAreClearErrors) {
  TempDir dir;
  const std::string path = dir.path() + "/bad.key";
  WriteFile(path, "public-key = \"" + std::string(kPublic) + "\"\n");
  Result<CurveKeyPair> missing = ReadKeyPair(path);
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(Contains(missing.status().message(), "no secret-key"));

  Result<CurveKeyPair> other = GenerateKeyPair();
  ASSERT_TRUE(other.ok());
  WriteFile(path, "public-key = \"" + std::string(kPublic) +
                      "\"\nsecret-key = \"" + other->secret_key + "\"\n");
  Result<CurveKeyPair> mismatched = ReadKeyPair(path);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_TRUE(Contains(mismatched.status().message(), "does not belong"));

  WriteFile(path, "public-key = tooshort\n");
  Result<std::string> short_key = ReadPublicKey(path);
  ASSERT_FALSE(short_key.ok());
  EXPECT_TRUE(Contains(short_key.status().message(), "Z85"));

  WriteFile(path, "# fine\nno equals sign here\n");
  Result<std::string> garbage = ReadPublicKey(path);
  ASSERT_FALSE(garbage.ok());
  EXPECT_TRUE(Contains(garbage.status().message(), path + ":2"));

  Result<std::string> absent = ReadPublicKey(dir.path() + "/absent.pub");
  ASSERT_FALSE(absent.ok());
  EXPECT_TRUE(Contains(absent.status().message(), "absent.pub"));
}

TEST(AllowListTest, ReadsKeysWithOptionalNamesAndSkipsComments) {
  TempDir dir;
  Result<CurveKeyPair> other = GenerateKeyPair();
  ASSERT_TRUE(other.ok());
  const std::string path = dir.path() + "/workers.allow";
  WriteFile(path, "# the cluster's workers\n\n" + std::string(kPublic) +
                      "   node-1 worker\n" + other->public_key + "\n");
  Result<std::map<std::string, std::string>> allowed = ReadAllowList(path);
  ASSERT_TRUE(allowed.ok()) << allowed.status().ToString();
  ASSERT_EQ(allowed->size(), 2u);
  EXPECT_EQ(allowed->at(kPublic), "node-1 worker");
  EXPECT_EQ(allowed->at(other->public_key), other->public_key);
}

TEST(AllowListTest, BadLinesAndEmptyListsAreRefused) {
  TempDir dir;
  const std::string path = dir.path() + "/workers.allow";
  WriteFile(path, std::string(kPublic) + "\nnot-a-key\n");
  Result<std::map<std::string, std::string>> bad = ReadAllowList(path);
  ASSERT_FALSE(bad.ok());
  EXPECT_TRUE(Contains(bad.status().message(), path + ":2"));

  WriteFile(path, "# nobody\n\n");
  Result<std::map<std::string, std::string>> empty = ReadAllowList(path);
  ASSERT_FALSE(empty.ok());
  EXPECT_TRUE(Contains(empty.status().message(), "no keys"));
}

TEST(LocalEndpointTest, OnlyLoopbackIpcAndInprocAreLocal) {
  for (const char* local :
       {"tcp://127.0.0.1:5555", "tcp://127.1.2.3:1", "tcp://localhost:5555",
        "tcp://[::1]:5555", "ipc:///tmp/animat.sock", "inproc://x",
        "tcp://127.0.0.1:*"}) {
    EXPECT_TRUE(IsLocalEndpoint(local)) << local;
  }
  for (const char* remote :
       {"tcp://*:5555", "tcp://0.0.0.0:5555", "tcp://10.0.0.1:5555",
        "tcp://eth0:5555", "tcp://node17.cluster:5555", "tcp://[::]:5555",
        "tcp://127.0.0.1.example.org:5555", "tcp://127.x.0.1:5555",
        "udp://127.0.0.1:5555", "tcp://[fe80::1]:5555"}) {
    EXPECT_FALSE(IsLocalEndpoint(remote)) << remote;
  }
}

}  // namespace
}  // namespace animat::security
