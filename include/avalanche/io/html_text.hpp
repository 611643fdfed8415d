#pragma once
// Text helpers of the self-contained HTML reports (report.html): escaping, base64 for
// data: URIs, number spelling, and inline SVG. No file access here.
#include <string>
#include <string_view>

namespace avalanche {

// Escapes & < > " ' for element text and attribute values, in HTML and in XML (the
// QGIS styles, qml_writer.cpp): ' becomes the character reference &#39;, which both read.
std::string html_escape(std::string_view text);

// RFC 4648 base64 (standard alphabet, '=' padding), for data: URIs.
std::string base64_encode(std::string_view bytes);

// A number for a reader, to at least 4 significant digits (so the relative rounding error
// is at most 5e-4): "%.4g" between 1e-3 and 1e4, whole numbers ("%.0f") from 1e4 to 1e15,
// "%.3e" for tiny and huge magnitudes; "0" for zero, "nan"/"inf" for non-finite values.
std::string format_number(double value);

// An SVG document ready to be placed inside HTML: drops an XML prolog and the xmlns
// attributes, which HTML5 does not need and which would put "http://" URLs into a file
// that must work offline.
std::string inline_svg(std::string svg);

}  // namespace avalanche
