// report.html, the planner's report (docs/products.md, "Planner's report"), end to end:
// (a) on a short avaKot run, every number marked data-key equals summary.json's value at
//     that key (to the 4 significant digits the report prints: relative tolerance 5e-4),
//     the file is offline (no http(s) URL, no absolute src), the input checksums equal
//     sha256sum's, the command line is quoted, the maps embed the quick-look PNGs with a
//     scale bar whose length is consistent with the geotransform;
// (b) headless Chromium renders it: a non-blank screenshot of the requested size, and every
//     map image decodes to the size of its PNG;
// and the batch report against comparison.csv. The map helpers are tested as functions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <sstream>

#include "avalanche/app/report_html.hpp"
#include "avalanche/app/report_html_map.hpp"
#include "batch_test_support.hpp"
#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;
using test::avaKot;
using test::read_json_file;
using test::read_text;
using test::run_binary;
using test::ScratchDir;

// format_number keeps at least 4 significant digits: half a unit in the 4th digit.
constexpr double kRelativeRounding = 5e-4;

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

std::string unescape(std::string s) {
    const std::pair<const char*, const char*> entities[] = {
        {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}};
    for (const auto& [from, to] : entities)
        for (auto p = s.find(from); p != std::string::npos; p = s.find(from, p + 1))
            s.replace(p, std::string(from).size(), to);
    return s;
}

// summary.json's value at a dotted key, independently of the report's own resolver.
const nlohmann::json* at_key(const nlohmann::json& root, const std::string& key) {
    const nlohmann::json* node = &root;
    std::stringstream parts(key);
    for (std::string part; std::getline(parts, part, '.');) {
        if (node->is_array() && !part.empty() &&
            std::isdigit(static_cast<unsigned char>(part[0])) && std::stoul(part) < node->size())
            node = &(*node)[std::stoul(part)];
        else if (node->is_object() && node->contains(part))
            node = &(*node)[part];
        else
            return nullptr;
    }
    return node;
}

struct Marked {
    std::string key, text;
};

std::vector<Marked> marked_values(const std::string& html) {
    std::vector<Marked> out;
    const std::regex re("data-key=\"([^\"]*)\">([^<]*)<");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator();
         ++it)
        out.push_back({unescape((*it)[1]), unescape((*it)[2])});
    return out;
}

std::vector<std::string> all_matches(const std::string& text, const std::string& pattern) {
    std::vector<std::string> out;
    const std::regex re(pattern);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
         ++it)
        out.push_back((*it)[1]);
    return out;
}

std::string base64_decode(const std::string& in) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        return c == '+' ? 62 : c == '/' ? 63 : -1;
    };
    std::string out;
    unsigned buffer = 0;
    int bits = 0;
    for (char c : in) {
        const int v = value(c);
        if (v < 0) continue;  // padding
        buffer = buffer << 6 | static_cast<unsigned>(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out += static_cast<char>((buffer >> bits) & 0xff);
        }
    }
    return out;
}

std::string command_output(const std::string& cmd) {
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    if (p == nullptr) return out;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    pclose(p);
    return out;
}

// A value of the report equals the summary's: strings exactly, booleans as yes / no,
// integers exactly, other numbers within the report's rounding.
void expect_same(const Marked& m, const nlohmann::json& v) {
    if (v.is_null()) {
        EXPECT_TRUE(m.text == "none" || m.text == "not reached") << m.key << ": " << m.text;
    } else if (v.is_string()) {
        EXPECT_EQ(m.text, v.get<std::string>()) << m.key;
    } else if (v.is_boolean()) {
        EXPECT_EQ(m.text, v.get<bool>() ? "yes" : "no") << m.key;
    } else if (v.is_number_integer() || v.is_number_unsigned()) {
        EXPECT_EQ(m.text, v.dump()) << m.key;
    } else if (v.is_number()) {
        const double expected = v.get<double>();
        double shown = std::nan("");
        try {
            shown = std::stod(m.text);
        } catch (const std::exception&) {
        }
        EXPECT_LE(std::abs(shown - expected), kRelativeRounding * std::abs(expected))
            << m.key << ": report " << m.text << ", summary " << v.dump();
    } else {
        ADD_FAILURE() << m.key << " marks a " << v.type_name() << ", not a single value";
    }
}

// One short avaKot run at 30 m with its monitoring point, shared by the checks below.
class HtmlReport : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = std::make_unique<ScratchDir>("html-report");
        out_ = dir_->file("out");
        std::ostringstream toml;
        toml << "[terrain]\ntype = \"dem\"\ndem = \"" << avaKot("avaKot_dem.tif")
             << "\"\n[release]\npolygons = \"" << avaKot("avaKot_release.gpkg")
             << "\"\nthickness_field = \"thickness\"\n[points]\nfile = \""
             << avaKot("avaKot_points.gpkg")
             << "\"\n[material]\ndensity = 300.0\n[numerics]\ncell_size = 30.0\nt_end = 30.0\n"
                "[output]\npressure_low_kpa = 4.5\npressure_high_kpa = 45.0\n";
        const std::string scenario = dir_->write("scenario.toml", toml.str());
        run_ = run_binary(*dir_, "run --scenario " + shell_quoted(scenario) + " --delta 24 --out " +
                                     shell_quoted(out_));
        if (run_.exit_code == 0) {
            html_ = read_text(out_ + "/report.html");
            summary_ = read_json_file(out_ + "/summary.json");
        }
    }
    static void TearDownTestSuite() { dir_.reset(); }
    void SetUp() override { ASSERT_EQ(run_.exit_code, 0) << run_.err; }

    static inline std::unique_ptr<ScratchDir> dir_;
    static inline std::string out_, html_;
    static inline nlohmann::json summary_;
    static inline test::ProcessResult run_;
};

TEST_F(HtmlReport, EveryMarkedNumberEqualsTheSummary) {
    const auto marked = marked_values(html_);
    ASSERT_GT(marked.size(), 50u);
    for (const auto& m : marked) {
        const nlohmann::json* v = at_key(summary_, m.key);
        ASSERT_NE(v, nullptr) << m.key << " is not a key of summary.json";
        expect_same(m, *v);
    }
    // The numbers a planner needs are among them.
    std::set<std::string> keys;
    for (const auto& m : marked) keys.insert(m.key);
    for (const char* key : {"runout.runout_length_m",
                            "runout.fall_height_m",
                            "runout.travel_angle_deg",
                            "runout.runout_efficiency",
                            "runout.affected_area_m2",
                            "runout.deposit_volume_m3",
                            "runout.max_depth_m",
                            "runout.max_velocity_ms",
                            "runout.max_pressure_kpa",
                            "volume.released_m3",
                            "volume.final_m3",
                            "volume.outflow_m3",
                            "volume.relative_error",
                            "end_reason",
                            "simulated_time_s",
                            "performance.cell_updates_per_s",
                            "software_version",
                            "source_hash",
                            "config_hash",
                            "command_line",
                            "parameters.material.delta_deg",
                            "parameters.output.pressure_low_kpa",
                            "parameters.output.pressure_high_kpa",
                            "monitoring_points.0.name",
                            "monitoring_points.0.max_pressure_kpa",
                            "inputs.0"})
        EXPECT_TRUE(keys.count(key)) << key << " is not in the report";
}

TEST_F(HtmlReport, IsSelfContained) {
    EXPECT_EQ(html_.find("http://"), std::string::npos);
    EXPECT_EQ(html_.find("https://"), std::string::npos);
    EXPECT_EQ(html_.find("src=\"/"), std::string::npos);
    EXPECT_EQ(html_.find("<script"), std::string::npos);
    EXPECT_EQ(html_.find("<link"), std::string::npos);
    const auto sources = all_matches(html_, "src=\"([^\"]{0,22})");
    ASSERT_EQ(sources.size(), 6u);  // the six maps
    for (const auto& s : sources) EXPECT_EQ(s.rfind("data:image/png;base64,", 0), 0u) << s;
}

TEST_F(HtmlReport, ChecksumsAreThoseOfSha256sum) {
    const std::regex re("data-file=\"([^\"]*)\">([0-9a-f]*)<");
    std::size_t files = 0;
    for (auto it = std::sregex_iterator(html_.begin(), html_.end(), re);
         it != std::sregex_iterator(); ++it, ++files) {
        const std::string path = unescape((*it)[1]);
        const std::string sum = command_output("sha256sum " + shell_quoted(path)).substr(0, 64);
        ASSERT_EQ(sum.size(), 64u) << "sha256sum failed on " << path;
        EXPECT_EQ((*it)[2].str(), sum) << path;
    }
    // DEM, release polygons and points.
    EXPECT_EQ(files, summary_["inputs"].size());
    EXPECT_EQ(files, 3u);
}

TEST_F(HtmlReport, QuotesTheCommandLine) {
    const std::string command = summary_["command_line"];
    EXPECT_NE(command.find("--delta 24"), std::string::npos) << command;
    const auto pre = all_matches(html_, "<pre class=\"v\" data-key=\"command_line\">([^<]*)</pre>");
    ASSERT_EQ(pre.size(), 1u);
    EXPECT_EQ(unescape(pre[0]), command);
}

TEST_F(HtmlReport, MapsAreTheQuickLooksWithAConsistentScaleBar) {
    // Each map element id="map-NAME" and the first base64 payload after it. Scanned by
    // hand: a lazy regex over the whole page recurses once per character in libstdc++
    // and overflowed the stack under AddressSanitizer.
    std::set<std::string> maps;
    const std::string tag = "id=\"map-", data = "base64,";
    for (auto at = html_.find(tag); at != std::string::npos; at = html_.find(tag, at + 1)) {
        const auto name_begin = at + tag.size();
        const std::string name = html_.substr(name_begin, html_.find('"', name_begin) - name_begin);
        const auto payload = html_.find(data, name_begin);
        ASSERT_NE(payload, std::string::npos) << name;
        const auto begin = payload + data.size();
        const std::string encoded = html_.substr(begin, html_.find('"', begin) - begin);
        maps.insert(name);
        EXPECT_EQ(base64_decode(encoded), read_text(out_ + "/" + name + ".png")) << name;
    }
    EXPECT_EQ(maps, (std::set<std::string>{"max_depth", "max_velocity", "max_pressure",
                                           "hazard_class", "arrival_time", "deposit_thickness"}));

    // Scale bar against the GeoTIFF's geotransform: a 1-2-5 length near a fifth of the map
    // width, drawn at the map's own pixels per metre.
    const test::Raster r = test::read_raster(out_ + "/max_depth.tif");
    const double width_m = r.width * r.gt[1];
    const auto lengths = all_matches(html_, "data-length-m=\"([0-9.e+]+)\"");
    const auto bars = all_matches(html_, "data-length-px=\"([0-9.]+)\"");
    const auto frames = all_matches(html_, "class=\"map-frame\" style=\"width:([0-9.]+)px");
    ASSERT_EQ(lengths.size(), 6u);
    ASSERT_EQ(bars.size(), 6u);
    ASSERT_EQ(frames.size(), 6u);
    const double length = std::stod(lengths[0]);
    const double mantissa = length / std::pow(10.0, std::floor(std::log10(length) + 1e-12));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 5) < 1e-9)
        << length;
    EXPECT_GE(length, width_m / 5 / std::sqrt(2.5));
    EXPECT_LE(length, width_m / 5 * std::sqrt(2.5));
    EXPECT_NEAR(std::stod(bars[0]) / std::stod(frames[0]), length / width_m,
                0.01 * length / width_m);

    // North arrow: the products are north-up in a projected CRS, and the caption names it.
    EXPECT_NE(html_.find("class=\"north-arrow\""), std::string::npos);
    GDALAllRegister();
    GDALDataset* tif = GDALDataset::Open((out_ + "/max_depth.tif").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(tif, nullptr);
    ASSERT_NE(tif->GetSpatialRef(), nullptr);
    const std::string crs_name = tif->GetSpatialRef()->GetName();
    GDALClose(tif);
    EXPECT_NE(html_.find("grid north of " + crs_name), std::string::npos)
        << "the caption should name the grid CRS, " << crs_name;
    // The release outline and the monitoring point are drawn on the maps.
    EXPECT_EQ(all_matches(html_, "<path class=\"release\" d=\"(M)").size(), 6u);
    const std::string point = summary_["monitoring_points"][0]["name"];
    EXPECT_GE(all_matches(html_, "(<g class=\"point\">)").size(), 6u);
    EXPECT_NE(html_.find(">" + point + "</text>"), std::string::npos);
    // avaKot's DEM covers 60 % of its grid: the notes explain the hatch of the rest.
    EXPECT_NE(html_.find("hatched with diagonals is outside the DEM's data"), std::string::npos);
}

TEST_F(HtmlReport, ExplainsTheHazardClassesWithTheRunsLimits) {
    // The run's own limits (4.5 and 45 kPa), marked, in the class table.
    for (const char* key :
         {"parameters.output.pressure_low_kpa", "parameters.output.pressure_high_kpa"})
        EXPECT_NE(html_.find(std::string("data-key=\"") + key + "\">"), std::string::npos) << key;
    EXPECT_NE(html_.find(">45</span> kPa or more"), std::string::npos);
    EXPECT_NE(html_.find("below <span class=\"v\" "
                         "data-key=\"parameters.output.pressure_low_kpa\">4.5</span> kPa"),
              std::string::npos);
    for (const char* words : {"high (red)", "medium (blue)", "low (yellow)", "not reached"})
        EXPECT_NE(html_.find(words), std::string::npos) << words;
}

TEST_F(HtmlReport, PlotsTheMonitoringSeries) {
    for (const char* title :
         {"Flow depth at the monitoring points", "Speed at the monitoring points",
          "Impact pressure at the monitoring points"})
        EXPECT_NE(html_.find(title), std::string::npos) << title;
    // One polyline per point and quantity, with as many vertices as the CSV has samples.
    const auto rows = test::lines_of(read_text(out_ + "/monitoring.csv"));
    const auto lines = all_matches(html_, "<polyline[^>]*points=\"([^\"]*)\"");
    ASSERT_EQ(lines.size(), 3u);
    for (const auto& l : lines) {
        std::size_t vertices = 0;
        for (char c : l) vertices += c == ',';
        EXPECT_EQ(vertices, rows.size() - 1);  // minus the header
    }
}

// --- (b) rendering in headless Chromium ---------------------------------------------------

std::string chromium() {
    for (const char* c :
         {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
        if (fs::exists(c)) return c;
    return "";
}

std::string chromium_command(const std::string& exe, const ScratchDir& dir,
                             const std::string& args) {
    // Root needs --no-sandbox; a fresh profile keeps runs independent.
    return shell_quoted(exe) +
           " --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run " +
           "--user-data-dir=" + shell_quoted(dir.file("profile")) + " " + args + " 2>/dev/null";
}

TEST_F(HtmlReport, ChromiumRendersANonBlankPage) {
    const std::string exe = chromium();
    if (exe.empty()) GTEST_SKIP() << "chromium is not installed (setup.sh installs it)";
    ScratchDir dir("html-render");
    const std::string shot = dir.file("shot.png");
    command_output(chromium_command(exe, dir,
                                    "--window-size=1200,3000 --screenshot=" + shell_quoted(shot) +
                                        " " + shell_quoted("file://" + out_ + "/report.html")));
    ASSERT_TRUE(fs::exists(shot)) << "no screenshot";
    GDALAllRegister();
    GDALDataset* png = GDALDataset::Open(shot.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(png, nullptr) << "not a readable PNG";
    EXPECT_EQ(png->GetRasterXSize(), 1200);
    EXPECT_EQ(png->GetRasterYSize(), 3000);
    std::vector<double> grey(static_cast<std::size_t>(png->GetRasterXSize()) *
                             png->GetRasterYSize());
    ASSERT_EQ(png->GetRasterBand(1)->RasterIO(
                  GF_Read, 0, 0, png->GetRasterXSize(), png->GetRasterYSize(), grey.data(),
                  png->GetRasterXSize(), png->GetRasterYSize(), GDT_Float64, 0, 0, nullptr),
              CE_None);
    GDALClose(png);
    double mean = 0, var = 0;
    for (double g : grey) mean += g;
    mean /= grey.size();
    for (double g : grey) var += (g - mean) * (g - mean);
    var /= grey.size();
    // A blank page has variance 0; text and maps on white give thousands (grey levels 0-255).
    EXPECT_GT(std::sqrt(var), 20.0) << "mean " << mean;
}

TEST_F(HtmlReport, ChromiumDecodesEveryMapImage) {
    const std::string exe = chromium();
    if (exe.empty()) GTEST_SKIP() << "chromium is not installed (setup.sh installs it)";
    ScratchDir dir("html-dom");
    // A copy with a probe script (the report itself has none): after loading, it records each
    // image's decoded width in the DOM that --dump-dom prints.
    std::string probe = html_;
    probe.insert(probe.rfind("</body>"),
                 "<script>window.addEventListener('load', () => document.body.setAttribute("
                 "'data-decoded', Array.from(document.images).map(i => i.naturalWidth + 'x' + "
                 "i.naturalHeight).join(' ')));</script>");
    const std::string page = dir.write("probe.html", probe);
    const std::string dom = command_output(chromium_command(
        exe, dir, "--virtual-time-budget=10000 --dump-dom " + shell_quoted("file://" + page)));
    EXPECT_EQ(all_matches(dom, "(<img class=\"map-image\")").size(), 6u);
    const auto decoded = all_matches(dom, "data-decoded=\"([^\"]*)\"");
    ASSERT_EQ(decoded.size(), 1u) << "the load handler did not run";
    const test::Raster r = test::read_raster(out_ + "/max_depth.tif");
    const std::string size = std::to_string(r.width) + "x" + std::to_string(r.height);
    std::string expected;
    for (int k = 0; k < 6; ++k) expected += (k ? " " : "") + size;
    EXPECT_EQ(decoded[0], expected);
}

// --- the map helpers as functions ----------------------------------------------------------

TEST(HtmlReportMap, ScaleBarIsTheOneTwoFiveLengthNearestAFifthOfTheWidth) {
    EXPECT_DOUBLE_EQ(scale_bar_length_m(1000.0), 200.0);   // a fifth exactly
    EXPECT_DOUBLE_EQ(scale_bar_length_m(437.0), 100.0);    // 87.4: 100 is nearer than 50
    EXPECT_DOUBLE_EQ(scale_bar_length_m(30.0), 5.0);       // 6: 5 is nearer than 10
    EXPECT_DOUBLE_EQ(scale_bar_length_m(7000.0), 1000.0);  // 1400: 1000 (x1.4) before 2000 (x1.43)
    EXPECT_DOUBLE_EQ(scale_bar_length_m(4.0), 1.0);        // 0.8 -> 1
    EXPECT_EQ(scale_bar_length_m(0.0), 0.0);
}

TEST(HtmlReportMap, OutlineFollowsTheCellEdgesNorthUp) {
    Grid g;
    g.nx = 3, g.ny = 2, g.dx = 10, g.dy = 10;
    // One release cell in the north-west corner (i = 0, j = 1): a 10 m square at the origin
    // of the display, which has 1 px per metre.
    std::vector<std::uint8_t> mask(g.cells(), 0);
    mask[1 * 3 + 0] = 1;
    EXPECT_EQ(outline_path(mask, g, 1.0),
              "M0.00 0.00h10.00M0.00 10.00h10.00M0.00 0.00v10.00M10.00 0.00v10.00");
    // Two neighbours share no edge: 6 edges.
    mask[1 * 3 + 1] = 1;
    const std::string two = outline_path(mask, g, 1.0);
    EXPECT_EQ(std::count(two.begin(), two.end(), 'M'), 6);
    EXPECT_EQ(outline_path(std::vector<std::uint8_t>(g.cells(), 0), g, 1.0), "");
}

TEST(HtmlReportMap, LegendListsTheClassesAndWhatIsNotColoured) {
    const std::string legend = legend_html(gis::depth_ramp({0.1, 0.5}), "depth, m");
    EXPECT_NE(legend.find("up to 0.1 m: not coloured"), std::string::npos) << legend;
    EXPECT_NE(legend.find("background:#c6dbef\"></span>0.1 - 0.5 m"), std::string::npos) << legend;
    EXPECT_NE(legend.find("&gt; 0.5 m"), std::string::npos) << legend;
    EXPECT_EQ(legend.find("no terrain data"), std::string::npos) << legend;
    const std::string hatched = legend_html(gis::depth_ramp({0.1, 0.5}), "depth, m", true);
    EXPECT_NE(hatched.find("swatch nodata\"></span>no terrain data (outside the DEM)"),
              std::string::npos)
        << hatched;
}

TEST(HtmlReportMap, NotesExplainTheHatchOnlyWhereTheTerrainHasNoData) {
    MapOverlay o;
    o.grid = Grid{4, 3, 10.0, 10.0};
    EXPECT_EQ(map_notes_html(o).find("outside the DEM's data"), std::string::npos);
    o.no_terrain_data = true;
    EXPECT_NE(map_notes_html(o).find("hatched with diagonals is outside the DEM's data"),
              std::string::npos);
}

// --- the batch report ----------------------------------------------------------------------

TEST(HtmlBatchReport, TableEqualsComparisonCsvAndTheFileIsSelfContained) {
    ScratchDir dir("html-batch");
    const std::string base = dir.write("base.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    const auto r =
        run_binary(dir, "batch --quiet --scenario " + shell_quoted(base) +
                            " --sweep delta=15,20 --parallel 1 --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string html = read_text(out + "/report.html");
    ASSERT_FALSE(html.empty());
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    EXPECT_EQ(html.find("src=\"/"), std::string::npos);

    // Every cell of comparison.csv, exactly in data-value and to the rounding in the text.
    const auto csv = test::read_csv(out + "/comparison.csv");
    ASSERT_EQ(csv.size(), 3u);
    std::size_t cells = 0;
    for (std::size_t row = 1; row < csv.size(); ++row)
        for (std::size_t c = 0; c < csv[0].size(); ++c, ++cells) {
            const std::string attrs = "data-id=\"" + csv[row][0] + "\" data-column=\"" + csv[0][c] +
                                      "\" data-value=\"" + csv[row][c] + "\">";
            const auto at = html.find(attrs);
            ASSERT_NE(at, std::string::npos) << attrs;
            if (c == 0) {
                EXPECT_EQ(html.compare(at + attrs.size(), 9, "<a href=\""), 0);  // links its report
                continue;
            }
            double v = 0;
            std::size_t used = 0;
            try {
                v = std::stod(csv[row][c], &used);
            } catch (const std::exception&) {
            }
            if (csv[row][c].empty() || used != csv[row][c].size()) continue;
            const double shown = std::stod(html.substr(at + attrs.size()));
            EXPECT_LE(std::abs(shown - v), kRelativeRounding * std::abs(v)) << attrs;
        }
    EXPECT_GT(cells, 10u);

    // The trend plots inline, the impact frequency drawn from its GeoTIFF.
    std::size_t svgs = 0;
    for (const auto& e : fs::directory_iterator(out)) svgs += e.path().extension() == ".svg";
    EXPECT_GE(svgs, 2u);
    EXPECT_GE(all_matches(html, "(<svg viewBox=\"0 0 640 420\")").size(), svgs);
    ASSERT_TRUE(fs::exists(out + "/impact_frequency.png"));
    const auto images = all_matches(html, "base64,([A-Za-z0-9+/=]+)\"");
    ASSERT_EQ(images.size(), 1u);
    EXPECT_EQ(base64_decode(images[0]), read_text(out + "/impact_frequency.png"));
    // Chute frame: no north arrow, and the caption says why.
    EXPECT_EQ(html.find("class=\"north-arrow\""), std::string::npos);
    EXPECT_NE(html.find("no geographic north"), std::string::npos);

    // A calibration written by the batch's --observed step is shown as a ranking table.
    std::ofstream(out + "/calibration.json")
        << R"({"observed": "deposit.gpkg", "ranking": [{"id": "delta=20", "score": 0.75},)"
        << R"( {"id": "delta=15", "score": 0.5}]})";
    write_batch_report_html(out, base, {"comparison.csv", "calibration.json"});
    const std::string with = read_text(out + "/report.html");
    EXPECT_NE(with.find("<td>deposit.gpkg</td>"), std::string::npos);
    EXPECT_NE(with.find("<tr><td>delta=20</td><td>0.75</td></tr>"), std::string::npos);
}

// A batch rerun into the folder of another with --overwrite: the plots, calibration and
// frequency map the first batch left there are not this batch's, and its report must not
// show them (it showed the first batch's calibration and delta plots beside its own).
TEST(HtmlBatchReport, ShowsOnlyWhatThisBatchWrote) {
    ScratchDir dir("html-batch-stale");
    const std::string base = dir.write("base.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    const std::string batch = "batch --quiet --scenario " + shell_quoted(base) + " --parallel 1 ";
    auto r = run_binary(dir, batch + "--sweep delta=15,20 --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(out + "/runout_vs_delta_deg.svg"));
    // As a batch with --observed leaves it.
    std::ofstream(out + "/calibration.json")
        << R"({"observed": "deposit.gpkg", "ranking": [{"id": "delta=20", "score": 0.75}]})";

    r = run_binary(dir, batch + "--sweep phi=30,35 --overwrite --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::string html = read_text(out + "/report.html");
    EXPECT_NE(html.find("vs phi_deg"), std::string::npos) << "this batch's plots";
    EXPECT_EQ(html.find("vs delta_deg"), std::string::npos) << "the first batch's plots";
    EXPECT_EQ(html.find("Calibration against the observation"), std::string::npos);
    EXPECT_EQ(html.find("deposit.gpkg"), std::string::npos);
    EXPECT_NE(html.find("id=\"frequency\""), std::string::npos);

    // A batch that wrote no plot and no frequency map (no scenario complete) shows none,
    // though DIR holds both.
    write_batch_report_html(out, base, {"comparison.csv", "comparison.md"});
    html = read_text(out + "/report.html");
    EXPECT_EQ(html.find("id=\"plots\""), std::string::npos);
    EXPECT_EQ(html.find("id=\"frequency\""), std::string::npos);
    EXPECT_EQ(html.find("id=\"calibration\""), std::string::npos);
    EXPECT_NE(html.find("id=\"comparison\""), std::string::npos);
}

}  // namespace
}  // namespace avalanche
