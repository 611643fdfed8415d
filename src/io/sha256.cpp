// SHA-256 by OpenSSL's libcrypto (the EVP digest interface of OpenSSL 3), which uses the
// processor's SHA extensions where it has them: a run's report hashes every input file,
// and a DEM mosaic can be gigabytes.
#include "avalanche/io/sha256.hpp"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {

// One digest in progress; the errors OpenSSL can report here (no memory, no SHA-256 in
// the library's provider) are not the input's fault.
class Sha256 {
  public:
    Sha256() : ctx_(EVP_MD_CTX_new()) {
        if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1)
            throw Error(ExitCode::internal, "OpenSSL cannot start a SHA-256 digest");
    }

    void update(const void* data, std::size_t n) {
        if (EVP_DigestUpdate(ctx_.get(), data, n) != 1)
            throw Error(ExitCode::internal, "OpenSSL's SHA-256 digest failed");
    }

    std::string hex_digest() {
        std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
        unsigned int size = 0;
        if (EVP_DigestFinal_ex(ctx_.get(), md.data(), &size) != 1 || size != 32)
            throw Error(ExitCode::internal, "OpenSSL's SHA-256 digest failed");
        std::string out;
        char buf[3];
        for (unsigned int k = 0; k < size; ++k) {
            std::snprintf(buf, sizeof buf, "%02x", md[k]);
            out += buf;
        }
        return out;
    }

  private:
    struct Free {
        void operator()(EVP_MD_CTX* c) const { EVP_MD_CTX_free(c); }
    };
    std::unique_ptr<EVP_MD_CTX, Free> ctx_;
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
    Sha256 s;
    s.update(bytes.data(), bytes.size());
    return s.hex_digest();
}

std::string sha256_file_hex(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "cannot be opened to compute its SHA-256 checksum");
    Sha256 s;
    std::array<char, 1 << 16> buf{};
    while (in) {
        in.read(buf.data(), buf.size());
        s.update(buf.data(), static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw InputError(path, "could not be read to the end for its SHA-256 checksum");
    return s.hex_digest();
}

}  // namespace avalanche
