// Escaping, base64 and number spelling for the HTML reports.
#include "avalanche/io/html_text.hpp"

#include <cmath>
#include <cstdio>

namespace avalanche {

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string base64_encode(std::string_view bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t k = 0;
    for (; k + 3 <= bytes.size(); k += 3) {
        const unsigned v = static_cast<unsigned char>(bytes[k]) << 16 |
                           static_cast<unsigned char>(bytes[k + 1]) << 8 |
                           static_cast<unsigned char>(bytes[k + 2]);
        for (int s = 18; s >= 0; s -= 6) out += kAlphabet[(v >> s) & 63];
    }
    const std::size_t rest = bytes.size() - k;
    if (rest > 0) {
        unsigned v = static_cast<unsigned char>(bytes[k]) << 16;
        if (rest == 2) v |= static_cast<unsigned char>(bytes[k + 1]) << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string format_number(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (value == 0.0) return "0";
    char buf[64];
    const double a = std::abs(value);
    if (a >= 1e-3 && a < 1e4)
        std::snprintf(buf, sizeof buf, "%.4g", value);
    else if (a >= 1e4 && a < 1e15)
        std::snprintf(buf, sizeof buf, "%.0f", value);
    else
        std::snprintf(buf, sizeof buf, "%.3e", value);
    return buf;
}

std::string inline_svg(std::string svg) {
    if (svg.rfind("<?xml", 0) == 0) {
        const auto end = svg.find("?>");
        svg.erase(0, end == std::string::npos ? svg.size() : end + 2);
    }
    for (const std::string attr : {" xmlns=\"", " xmlns:xlink=\""}) {
        for (auto pos = svg.find(attr); pos != std::string::npos; pos = svg.find(attr, pos)) {
            const auto close = svg.find('"', pos + attr.size());
            if (close == std::string::npos) break;
            svg.erase(pos, close + 1 - pos);
        }
    }
    const auto start = svg.find('<');
    if (start == std::string::npos) return "";
    svg.erase(0, start);
    // A viewBox from the width and height, so that CSS can scale the plot.
    const auto tag_end = svg.find('>');
    const std::string tag = svg.substr(0, tag_end);
    auto attribute = [&](const std::string& name) {
        const auto p = tag.find(" " + name + "=\"");
        if (p == std::string::npos) return std::string();
        const auto from = p + name.size() + 3;
        return tag.substr(from, tag.find('"', from) - from);
    };
    const std::string w = attribute("width"), h = attribute("height");
    if (svg.rfind("<svg", 0) == 0 && attribute("viewBox").empty() && !w.empty() && !h.empty() &&
        w.find_first_not_of("0123456789.") == std::string::npos &&
        h.find_first_not_of("0123456789.") == std::string::npos)
        svg.insert(4, " viewBox=\"0 0 " + w + " " + h + "\"");
    return svg;
}

}  // namespace avalanche
