#include "toml_section.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche::detail {

std::string describe_type(const toml::node& node) {
    switch (node.type()) {
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
            return "an integer";
        case toml::node_type::floating_point:
            return "a number";
        case toml::node_type::boolean:
            return "a boolean";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::table:
            return "a table";
        case toml::node_type::date:
        case toml::node_type::time:
        case toml::node_type::date_time:
            return "a date/time";
        case toml::node_type::none:
            break;
    }
    return "nothing";
}

std::string printable(std::string_view text) {
    static const char* kHex = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else if (u < 0x20 || u == 0x7f) {
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 0xf];
        } else {
            out += c;
        }
    }
    return out;
}

TomlSection::TomlSection(const toml::table* table, std::string name, std::string file_label)
    : table_(table), name_(std::move(name)), file_label_(std::move(file_label)) {}

bool TomlSection::has(std::string_view key) const {
    return table_ != nullptr && table_->contains(key);
}

void TomlSection::fail(std::string_view key, const std::string& what) const {
    throw ConfigError(file_label_ + ": " + name_ + "." + printable(key), printable(what));
}

const toml::node* TomlSection::get(std::string_view key) {
    if (!table_) return nullptr;
    read_.emplace(key);
    return table_->get(key);
}

std::optional<double> TomlSection::number(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_number()) fail(key, "expected a number, got " + describe_type(*n));
    return n->value<double>();
}

std::optional<std::int64_t> TomlSection::integer(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer()) fail(key, "expected an integer, got " + describe_type(*n));
    return n->value<std::int64_t>();
}

std::optional<bool> TomlSection::boolean(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_boolean()) fail(key, "expected true or false, got " + describe_type(*n));
    return n->value<bool>();
}

std::optional<std::string> TomlSection::text(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "expected a string, got " + describe_type(*n));
    return n->value<std::string>();
}

std::optional<std::array<double, 2>> TomlSection::pair(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    const toml::array* a = n->as_array();
    if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
        fail(key, "expected an array of two numbers, e.g. [1.0, 2.0]");
    return std::array<double, 2>{*(*a)[0].value<double>(), *(*a)[1].value<double>()};
}

std::optional<std::vector<std::string>> TomlSection::text_or_list(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (n->is_string()) return std::vector<std::string>{*n->value<std::string>()};
    const toml::array* a = n->as_array();
    if (!a || a->empty() || !a->is_homogeneous(toml::node_type::string))
        fail(key, "expected a file name or a non-empty array of file names");
    std::vector<std::string> out;
    for (const auto& e : *a) out.push_back(*e.value<std::string>());
    return out;
}

void TomlSection::refuse_unread_keys(const std::string& context) const {
    if (!table_) return;
    for (const auto& [key, node] : *table_) {
        if (read_.find(key.str()) == read_.end()) fail(key.str(), "unknown key (" + context + ")");
    }
}

}  // namespace avalanche::detail
