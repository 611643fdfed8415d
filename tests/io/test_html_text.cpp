// The text helpers of report.html: base64 against RFC 4648 section 10, escaping, the
// rounding promise of format_number, and inline SVG without namespace URLs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "avalanche/io/html_text.hpp"

namespace avalanche {
namespace {

TEST(HtmlText, Base64MatchesRfc4648TestVectors) {
    EXPECT_EQ(base64_encode(""), "");
    EXPECT_EQ(base64_encode("f"), "Zg==");
    EXPECT_EQ(base64_encode("fo"), "Zm8=");
    EXPECT_EQ(base64_encode("foo"), "Zm9v");
    EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
    EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
    EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
    // High bytes must not sign-extend: 0xFF 0xFE 0xFD is "//79".
    EXPECT_EQ(base64_encode("\xff\xfe\xfd"), "//79");
}

TEST(HtmlText, EscapeCoversMarkupAndQuotes) {
    EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

TEST(HtmlText, FormattedNumbersAreWithinHalfAUnitInTheFourthDigit) {
    for (double v : {0.0, 1.0, -2.5, 1234.5678, 0.0123456, 9999.96, 12345.678, 3.2e7, 1.234567e-16,
                     -7.77777e-5, 2.5e16}) {
        const std::string text = format_number(v);
        const double back = std::stod(text);
        EXPECT_LE(std::abs(back - v), 5e-4 * std::abs(v)) << v << " -> " << text;
    }
    // Whole numbers from 1e4 up (areas in m2), plain decimals below, no exponent for a reader.
    EXPECT_EQ(format_number(123456.7), "123457");
    EXPECT_EQ(format_number(0.25), "0.25");
    EXPECT_EQ(format_number(1.5e-7), "1.500e-07");
}

TEST(HtmlText, InlineSvgDropsPrologAndNamespaces) {
    const std::string svg = inline_svg(
        "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
        "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"10\"><rect/></svg>\n");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u) << svg;
    EXPECT_EQ(svg.find("http"), std::string::npos) << svg;
    EXPECT_NE(svg.find("width=\"10\"><rect/></svg>"), std::string::npos) << svg;
    // Width and height give the viewBox that lets CSS scale the plot.
    EXPECT_EQ(inline_svg("<svg width=\"640\" height=\"420\"><g/></svg>"),
              "<svg viewBox=\"0 0 640 420\" width=\"640\" height=\"420\"><g/></svg>");
}

}  // namespace
}  // namespace avalanche
