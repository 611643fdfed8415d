#pragma once
// SHA-256 (FIPS 180-4) of a byte string or a file, as 64 lower-case hex digits: the
// checksums of a run's input files in its report, so that a reader can tell whether the
// DEM and release they hold are the ones the maps were computed from. Computed by
// OpenSSL's libcrypto (sha256.cpp).
#include <string>
#include <string_view>

namespace avalanche {

std::string sha256_hex(std::string_view bytes);

// Reads the file in blocks; InputError naming the file when it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace avalanche
