#pragma once
// The spelling of every model choice in scenario files, flags and outputs, in one
// table per enum, so that the TOML reader, the command line and the writers agree.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/material.hpp"

namespace avalanche {

template <class E, std::size_t N>
using EnumNames = std::array<std::pair<std::string_view, E>, N>;

inline constexpr EnumNames<Scheme, 2> kSchemeNames{
    {{"waf", Scheme::waf}, {"godunov", Scheme::godunov}}};
inline constexpr EnumNames<Limiter, 4> kLimiterNames{{{"van_leer", Limiter::van_leer},
                                                      {"superbee", Limiter::superbee},
                                                      {"van_albada", Limiter::van_albada},
                                                      {"minmod", Limiter::minmod}}};
inline constexpr EnumNames<Boundary, 2> kBoundaryNames{
    {{"open", Boundary::open}, {"wall", Boundary::wall}}};
inline constexpr EnumNames<Splitting, 2> kSplittingNames{
    {{"lsl", Splitting::lsl}, {"sls", Splitting::sls}}};
inline constexpr EnumNames<EarthPressureModel, 2> kEarthPressureNames{
    {{"savage-hutter", EarthPressureModel::savage_hutter},
     {"isotropic", EarthPressureModel::isotropic}}};

template <class E, std::size_t N>
[[nodiscard]] std::optional<E> enum_from_name(const EnumNames<E, N>& names, std::string_view s) {
    for (const auto& [name, value] : names)
        if (name == s) return value;
    return std::nullopt;
}

template <class E, std::size_t N>
[[nodiscard]] std::string enum_name(const EnumNames<E, N>& names, E value) {
    for (const auto& [name, v] : names)
        if (v == value) return std::string(name);
    return "unknown";
}

// "one of \"waf\", \"godunov\"", for error messages and --help.
template <class E, std::size_t N>
[[nodiscard]] std::string enum_choices(const EnumNames<E, N>& names) {
    std::string out = "one of ";
    for (std::size_t k = 0; k < N; ++k) {
        if (k) out += ", ";
        out.append(1, '"').append(names[k].first).append(1, '"');
    }
    return out;
}

}  // namespace avalanche
