// monitoring.csv and monitoring.h5 for points whose names come from GeoJSON or GeoPackage
// attributes, which may hold commas, quotes and line breaks.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "avalanche/io/csv_text.hpp"
#include "avalanche/io/monitoring_writer.hpp"
#include "avalanche/output/monitoring.hpp"
#include "io_test_support.hpp"

namespace avalanche {
namespace {

// An RFC 4180 reader written for the test, independently of the writer: quoted fields
// may hold commas, doubled quotes and line breaks.
std::vector<std::vector<std::string>> parse_rfc4180(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false;
    for (std::size_t k = 0; k < text.size(); ++k) {
        const char c = text[k];
        if (quoted) {
            if (c != '"') {
                field += c;
            } else if (k + 1 < text.size() && text[k + 1] == '"') {
                field += '"';
                ++k;
            } else {
                quoted = false;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            row.push_back(field);
            field.clear();
        } else if (c == '\n') {
            row.push_back(field);
            field.clear();
            rows.push_back(row);
            row.clear();
        } else {
            field += c;
        }
    }
    return rows;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

MonitoringPoints two_samples_at(const std::vector<std::string>& names) {
    std::vector<ProbeLocation> locations;
    for (std::size_t p = 0; p < names.size(); ++p)
        locations.push_back({names[p], 10.0 * static_cast<double>(p), 5.0, static_cast<int>(p), 0});
    MonitoringPoints points(locations, 0.1, 300.0, 0.01);
    CheckpointData c;
    c.integers["monitoring/sample_counts"] = std::vector<std::int64_t>(names.size(), 2);
    for (std::size_t p = 0; p < names.size(); ++p)
        for (const double t : {0.0, 0.1})
            c.reals["monitoring/samples"].insert(c.reals["monitoring/samples"].end(),
                                                 {t, 1.5, 2.0, 0.0, 2.0, 1.2});
    c.reals["monitoring/next_sample_time"] = {0.2};
    points.restore(c);
    return points;
}

TEST(MonitoringWriter, CsvQuotesNamesWithCommasQuotesAndLineBreaks) {
    test::ScratchDir dir("monitoring-csv");
    const std::vector<std::string> names = {"Haus Moser, Nord", "Rinne \"Ost\"", "Galerie\r\nWest",
                                            "plain"};
    write_monitoring_csv(dir.file("monitoring.csv"), two_samples_at(names));
    const std::string text = read_text(dir.file("monitoring.csv"));
    const auto rows = parse_rfc4180(text);
    ASSERT_EQ(rows.size(), 1 + 2 * names.size()) << text;
    ASSERT_EQ(rows[0].size(), 9u);
    for (std::size_t r = 1; r < rows.size(); ++r) {
        EXPECT_EQ(rows[r].size(), rows[0].size()) << "row " << r << " of\n" << text;
        EXPECT_EQ(rows[r][0], names[(r - 1) / 2]) << "row " << r;
    }
    // Ordinary names are written as before, unquoted.
    EXPECT_NE(text.find("\nplain,30,5,0,"), std::string::npos) << text;
    EXPECT_NE(text.find("\n\"Rinne \"\"Ost\"\"\",10,5,"), std::string::npos) << text;
}

TEST(MonitoringWriter, CsvFieldQuotesOnlyWhatItMust) {
    EXPECT_EQ(csv_field("Lift 3"), "Lift 3");
    EXPECT_EQ(csv_field(""), "");
    EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
    EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
    EXPECT_EQ(csv_field("lf\n"), "\"lf\n\"");
}

TEST(MonitoringWriter, Hdf5HasOneGroupPerNameWithCommasAndQuotes) {
    test::ScratchDir dir("monitoring-h5");
    const std::vector<std::string> names = {"Haus Moser, Nord", "Rinne \"Ost\"", ".."};
    write_monitoring_hdf5(dir.file("monitoring.h5"), two_samples_at(names));
    for (const auto& name : names) {
        const auto t = test::read_h5_dataset(dir.file("monitoring.h5"), name + "/t");
        EXPECT_EQ(t.values, (std::vector<double>{0.0, 0.1})) << name;
    }
}

}  // namespace
}  // namespace avalanche
