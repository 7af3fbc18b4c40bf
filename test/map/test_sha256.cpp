// SHA-256 against the FIPS 180-4 / NIST example vectors, incl. multi-block and chunked updates.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "radarslam/map/sha256.h"

using radarslam::Sha256;
using radarslam::sha256Hex;

TEST(Sha256, NistVectors) {
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(
      sha256Hex(
          "abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopq"
          "rsmnopqrstnopqrstu"),
      "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
  EXPECT_EQ(sha256Hex(std::string(1'000'000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, ChunkedUpdatesEqualOneShot) {
  std::string data;
  for (int i = 0; i < 1000; ++i) data.push_back(static_cast<char>(i * 31 + 7));
  const std::string expected = sha256Hex(data);
  for (std::size_t chunk : {1u, 3u, 55u, 56u, 63u, 64u, 65u, 500u}) {
    Sha256 h;
    for (std::size_t i = 0; i < data.size(); i += chunk) h.update(std::string_view(data).substr(i, chunk));
    EXPECT_EQ(h.hexDigest(), expected) << "chunk " << chunk;
  }
  // Lengths around the padding boundary (55/56/64 bytes) differ from each other.
  EXPECT_NE(sha256Hex(std::string(55, 'x')), sha256Hex(std::string(56, 'x')));
}

TEST(Sha256, HexRoundTripAndStrictForm) {
  Sha256 h;
  h.update("abc");
  const auto bytes = h.digest();
  const std::string hex = radarslam::toHex(bytes);
  EXPECT_EQ(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_TRUE(radarslam::isSha256Hex(hex));
  const auto back = radarslam::sha256FromHex(hex);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, bytes);
  // Only 64 lower-case hex digits are a SHA-256 of the map format.
  for (const std::string& bad : {hex.substr(1), hex + "0", std::string("BA") + hex.substr(2),
                                 std::string("g") + hex.substr(1), std::string(" ") + hex.substr(1)}) {
    EXPECT_FALSE(radarslam::isSha256Hex(bad)) << bad;
    EXPECT_FALSE(radarslam::sha256FromHex(bad).has_value()) << bad;
  }
  EXPECT_EQ(radarslam::toHex(std::array<unsigned char, 3>{0x00, 0x0f, 0xf0}), "000ff0");
}
