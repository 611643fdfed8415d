#pragma once
// Typed, strict access to one table of a scenario file: every value is checked for
// its type, every key that nobody asked for is refused, and every error names the
// file and the key ("scenario.toml: numerics.cfl: expected a number, got a string").
#include <toml++/toml.h>

#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "avalanche/io/enum_names.hpp"

namespace avalanche::detail {

class TomlSection {
  public:
    // table may be null (section absent): every getter then returns nullopt.
    TomlSection(const toml::table* table, std::string name, std::string file_label);

    [[nodiscard]] bool present() const { return table_ != nullptr; }
    [[nodiscard]] bool has(std::string_view key) const;

    std::optional<double> number(std::string_view key);
    std::optional<std::int64_t> integer(std::string_view key);
    std::optional<bool> boolean(std::string_view key);
    std::optional<std::string> text(std::string_view key);
    std::optional<std::array<double, 2>> pair(std::string_view key);
    // A string or an array of strings (e.g. one DEM tile or several).
    std::optional<std::vector<std::string>> text_or_list(std::string_view key);

    template <class E, std::size_t N>
    std::optional<E> choice(std::string_view key, const EnumNames<E, N>& names) {
        const auto s = text(key);
        if (!s) return std::nullopt;
        if (auto e = enum_from_name(names, *s)) return e;
        fail(key, "expected " + enum_choices(names) + ", got \"" + *s + "\"");
    }

    // Refuses the first key that was not read; `context` explains what was expected
    // (e.g. "shape = \"cap\" takes center, radius").
    void refuse_unread_keys(const std::string& context) const;

    [[noreturn]] void fail(std::string_view key, const std::string& what) const;

  private:
    const toml::node* get(std::string_view key);

    const toml::table* table_;
    std::string name_;
    std::string file_label_;
    std::set<std::string, std::less<>> read_;
};

// "a string", "an integer", ... for "expected X, got Y" messages.
std::string describe_type(const toml::node& node);

// `text` with control characters escaped ("\n", "\x01"): keys, values and parser
// messages quote the file's own bytes, and an error must stay one line (docs/cli.md).
std::string printable(std::string_view text);

}  // namespace avalanche::detail
