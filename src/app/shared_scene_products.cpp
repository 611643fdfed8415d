#include "avalanche/app/shared_scene_products.hpp"

#include <spdlog/spdlog.h>

#include <system_error>

namespace avalanche {

const gis::QuicklookShade& SharedSceneProducts::shade(
    const std::function<gis::QuicklookShade()>& make) {
    const std::lock_guard lock(shade_mutex_);
    if (!shade_) shade_ = make();
    return *shade_;
}

void SharedSceneProducts::dem(const std::filesystem::path& target,
                              const std::function<void()>& write) {
    // Held while the first file is written: the scenarios waiting here would otherwise
    // each write the same file.
    const std::lock_guard lock(dem_mutex_);
    if (!dem_.empty()) {
        const std::filesystem::path part = target.string() + ".part";
        std::error_code ec;
        std::filesystem::remove(part, ec);
        std::filesystem::create_hard_link(dem_, part, ec);
        if (!ec) std::filesystem::rename(part, target, ec);
        if (!ec) return;
        spdlog::debug("{}: not linked to {} ({}); written", target.string(), dem_.string(),
                      ec.message());
        std::filesystem::remove(part, ec);
    }
    write();
    dem_ = target;
}

}  // namespace avalanche
