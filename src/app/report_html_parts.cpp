// Keyed values, the page skeleton and its stylesheet for report.html.
#include "report_html_parts.hpp"

#include <fstream>
#include <sstream>

#include "avalanche/io/html_text.hpp"

namespace avalanche::detail {

const nlohmann::json* json_at(const nlohmann::json& root, const std::string& dotted_key) {
    const nlohmann::json* node = &root;
    std::istringstream parts(dotted_key);
    for (std::string part; std::getline(parts, part, '.');) {
        if (node->is_object()) {
            const auto it = node->find(part);
            if (it == node->end()) return nullptr;
            node = &*it;
        } else if (node->is_array()) {
            if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
                return nullptr;
            const std::size_t k = std::stoul(part);
            if (k >= node->size()) return nullptr;
            node = &(*node)[k];
        } else {
            return nullptr;
        }
    }
    return node;
}

std::string json_text(const nlohmann::json& v, const std::string& null_text) {
    if (v.is_null()) return null_text;
    if (v.is_string()) return v.get<std::string>();
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
    if (v.is_number()) return format_number(v.get<double>());
    if (v.is_array()) {
        std::string out;
        for (const auto& e : v) out += (out.empty() ? "" : ", ") + json_text(e, null_text);
        return out;
    }
    return v.dump();
}

std::string keyed(const nlohmann::json& root, const std::string& key, const char* tag,
                  const std::string& null_text) {
    const nlohmann::json* v = json_at(root, key);
    if (v == nullptr) return std::string("<") + tag + ">n/a</" + tag + ">";
    return std::string("<") + tag + " class=\"v\" data-key=\"" + html_escape(key) + "\">" +
           html_escape(json_text(*v, null_text)) + "</" + tag + ">";
}

namespace {

// Print-friendly, readable without a wide screen: one column, tables with rules, maps
// at their natural size with the legend beside them.
constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Arial, sans-serif; color: #222; max-width: 1040px;
       margin: 0 auto; padding: 16px 24px 48px; line-height: 1.45; }
h1 { font-size: 1.7em; margin-bottom: 0.2em; }
h2 { border-bottom: 2px solid #555; padding-bottom: 3px; margin-top: 2em; }
h3 { margin: 0.4em 0; }
.subtitle { color: #555; margin-top: 0; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border-bottom: 1px solid #ccc; padding: 3px 10px 3px 4px; text-align: left;
         vertical-align: top; }
th { background: #f0f0f0; }
td.n, th.n { text-align: right; }
.brief { background: #f6f6f0; border-left: 4px solid #888; padding: 8px 14px; }
figure.map { margin: 1.2em 0 2em; page-break-inside: avoid; }
.map-row { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
.map-frame { position: relative; flex: none; border: 1px solid #888; }
.map-image { display: block; image-rendering: pixelated; }
.overlay { position: absolute; left: 0; top: 0; }
.legend ul { list-style: none; padding: 0; margin: 4px 0; }
.legend li { margin: 2px 0; white-space: nowrap; }
.legend-title { font-weight: bold; }
.swatch { display: inline-block; width: 22px; height: 14px; margin-right: 8px;
          border: 1px solid #666; vertical-align: middle; }
.swatch.none { background: linear-gradient(90deg, #aaa, #f2f2f2); }
.swatch.nodata { background: repeating-linear-gradient(135deg, #b8b8b8 0 1px, #ededed 1px 6px); }
figcaption { color: #444; font-size: 0.92em; max-width: 900px; margin-top: 6px; }
.classes td:first-child { white-space: nowrap; }
.plots { display: flex; flex-wrap: wrap; gap: 8px 16px; }
.plots svg { width: 490px; max-width: 100%; height: auto; }
pre { background: #f4f4f4; padding: 8px; white-space: pre-wrap; word-break: break-all; }
code, .hash { font-family: "DejaVu Sans Mono", monospace; font-size: 0.9em; }
.missing { color: #a00; }
.wide { overflow-x: auto; max-width: 100%; }
table.comparison { font-size: 0.82em; }
table.comparison th { min-width: 3em; }
.note { color: #555; font-size: 0.92em; }
.caveats { border: 3px solid #e08a00; padding: 0.6em; }
)";

}  // namespace

std::string html_document(const std::string& title, const std::string& body) {
    return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
           html_escape(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" +
           body + "\n</body>\n</html>\n";
}

std::string read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace avalanche::detail
