#include "avalanche/io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {

// The .part is ours: after a failure nothing half-written stays behind (a full disk
// must not leave files that a later run or a user could take for results).
[[noreturn]] void fail(const std::string& part, const std::string& path, const std::string& what) {
    std::error_code ec;
    std::filesystem::remove(part, ec);
    throw OutputError(path, what);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& content) {
    const std::string part = path + ".part";
    // stdio rather than a stream: fwrite and fclose report errno (ENOSPC, EFBIG), and
    // fclose is where buffered bytes finally reach the disk.
    std::FILE* f = std::fopen(part.c_str(), "wb");
    if (f == nullptr)
        fail(part, path, std::string("cannot create the file: ") + std::strerror(errno));
    const std::size_t written = std::fwrite(content.data(), 1, content.size(), f);
    int err = written == content.size() ? 0 : errno;
    if (std::fflush(f) != 0 && err == 0) err = errno;
    if (std::fclose(f) != 0 && err == 0) err = errno;
    if (err != 0 || written != content.size())
        fail(part, path,
             std::string("cannot write the file (disk full?): ") + std::strerror(err ? err : EIO));
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) fail(part, path, "cannot move the finished file into place: " + ec.message());
}

}  // namespace avalanche
