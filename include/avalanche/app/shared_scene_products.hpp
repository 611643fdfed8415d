#pragma once
// What the products of the scenarios of one prepared scene have in common (`batch`,
// docs/batch.md): the hillshade under every quick-look and the computational DEM,
// dem.tif, depend on the scene alone. The first scenario to write its products makes
// them; the others reuse the shade and get a hard link to its dem.tif. On an ASTER-size
// grid dem.tif is 11 MB and a second of writing per scenario.
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>

#include "avalanche/gis/quicklook.hpp"

namespace avalanche {

class SharedSceneProducts {
  public:
    // The quick-looks' shade, made by `make` on the first call; the same object after.
    const gis::QuicklookShade& shade(const std::function<gis::QuicklookShade()>& make);

    // Puts `target` (a scenario's dem.tif) in place: a hard link to the first one written,
    // made beside the target and renamed over it (atomic, as every product is), or, the
    // first time and whenever linking fails (another file system, the first file gone),
    // the file `write` writes at `target`. Files are never written in place (they are
    // renamed into place), so a later scenario replacing its link leaves the others'.
    void dem(const std::filesystem::path& target, const std::function<void()>& write);

  private:
    std::mutex shade_mutex_, dem_mutex_;
    std::optional<gis::QuicklookShade> shade_;
    std::filesystem::path dem_;  // the first dem.tif written; empty before
};

}  // namespace avalanche
