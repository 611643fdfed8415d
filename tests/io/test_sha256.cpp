// SHA-256 against the FIPS 180-4 examples (NIST "Example Algorithm Implementations",
// SHA256.pdf and the secure-hashing test vectors), and against coreutils' sha256sum for
// messages on the padding boundaries (55, 56, 63, 64 bytes) and a multi-block file.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/io/sha256.hpp"
#include "support/scratch_dir.hpp"

namespace avalanche {
namespace {

TEST(Sha256, FipsExampleOneBlock) {
    EXPECT_EQ(sha256_hex("abc"),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, FipsExampleTwoBlocks) {
    EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, EmptyMessage) {
    EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, OneMillionA) {
    EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

std::string sha256sum_of(const std::string& path) {
    const std::string cmd = "sha256sum '" + path + "'";
    FILE* p = popen(cmd.c_str(), "r");
    if (p == nullptr) return "";
    char buf[65] = {};
    const std::size_t n = std::fread(buf, 1, 64, p);
    pclose(p);
    return std::string(buf, n);
}

TEST(Sha256, FilesOnPaddingBoundariesAgreeWithSha256sum) {
    test::ScratchDir dir("sha256");
    for (std::size_t n : {55u, 56u, 63u, 64u, 65u, 200000u}) {
        std::string text;
        for (std::size_t k = 0; k < n; ++k) text += static_cast<char>((k * 131 + 7) % 256);
        // Named with += : GCC 12 warns (-Wrestrict, falsely) on "f" + std::to_string(n).
        std::string name = "f";
        name += std::to_string(n);
        const std::string path = dir.write(name, text);
        const std::string expected = sha256sum_of(path);
        ASSERT_EQ(expected.size(), 64u) << "sha256sum unavailable";
        EXPECT_EQ(sha256_file_hex(path), expected) << n << " bytes";
        EXPECT_EQ(sha256_hex(text), expected) << n << " bytes";
    }
}

TEST(Sha256, MissingFileIsAnInputErrorNamingIt) {
    try {
        sha256_file_hex("/nonexistent/dem.tif");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/dem.tif"), std::string::npos);
    }
}

}  // namespace
}  // namespace avalanche
