#include "avalanche/io/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "avalanche/core/error.hpp"

namespace avalanche {

void write_file_atomically(const std::string& path, const std::string& content) {
    const std::string part = path + ".part";
    {
        std::ofstream out(part, std::ios::binary | std::ios::trunc);
        if (!out) throw OutputError(part, "cannot create the file");
        out << content;
        out.flush();
        if (!out) throw OutputError(part, "cannot write the file (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) throw OutputError(path, "cannot move the finished file into place: " + ec.message());
}

}  // namespace avalanche
