#pragma once
// Writes a whole text file so that readers see either the old file or the new one,
// never half of it: write `path`.part, flush, rename over `path`.
#include <string>

namespace avalanche {

// Throws OutputError naming the path on any failure.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace avalanche
