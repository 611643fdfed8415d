// Parsing of --sweep and --table into batch cases, and how the command refuses bad ones
// (exit 2, the message names the --sweep value, nothing written).
#include <gtest/gtest.h>

#include <filesystem>

#include "avalanche/app/batch_plan.hpp"
#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"
#include "batch_test_support.hpp"

namespace avalanche {
namespace {

std::string config_error_of(const std::string& spec) {
    try {
        parse_sweep(spec);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(BatchSweep, ListsKeepTheirOrderInShortestSpelling) {
    const Sweep s = parse_sweep("delta=10,12.50,15,20");
    EXPECT_STREQ(s.parameter->column, "delta_deg");
    EXPECT_EQ(s.values, (std::vector<std::string>{"10", "12.5", "15", "20"}));
    EXPECT_EQ(parse_sweep("scheme=waf,godunov").values,
              (std::vector<std::string>{"waf", "godunov"}));
}

TEST(BatchSweep, RangesIncludeTheStopDespiteRoundOff) {
    EXPECT_EQ(parse_sweep("delta=5:20:2.5").values,
              (std::vector<std::string>{"5", "7.5", "10", "12.5", "15", "17.5", "20"}));
    // 0.1 + 2 * 0.1 = 0.30000000000000004 in binary floating point.
    EXPECT_EQ(parse_sweep("cfl=0.1:0.3:0.1").values,
              (std::vector<std::string>{"0.1", "0.2", "0.3"}));
    EXPECT_EQ(parse_sweep("phi=30:31:2").values, (std::vector<std::string>{"30"}));
}

TEST(BatchSweep, BadSyntaxAndUnknownParametersNameTheSweep) {
    for (const char* bad :
         {"delta", "delta=", "=5", "delta=1:2", "delta=a,b", "delta=5:1:1", "delta=1:5:0",
          "delta=1,,2", "scheme=1:2:1", "limiter=1:2:1", "delta=10,10.0", "friction=10",
          "cell_size=0.5", "quality=draft,fine"}) {
        const std::string message = config_error_of(bad);
        EXPECT_NE(message.find(std::string("--sweep ") + bad), std::string::npos)
            << bad << " -> " << message;
    }
    EXPECT_NE(config_error_of("cell_size=0.5").find("grid"), std::string::npos);
    EXPECT_NE(config_error_of("quality=draft,fine").find("change the cell size"), std::string::npos);
}

TEST(BatchSweep, CartesianProductHasFilesystemSafeIds) {
    const auto cases = cartesian_product({parse_sweep("delta=10,12.5"), parse_sweep("phi=30,35")});
    std::vector<std::string> ids;
    for (const auto& c : cases) ids.push_back(c.id);
    EXPECT_EQ(ids, (std::vector<std::string>{"delta=10_phi=30", "delta=10_phi=35",
                                             "delta=12.5_phi=30", "delta=12.5_phi=35"}));
    EXPECT_THROW(cartesian_product({parse_sweep("delta=10"), parse_sweep("delta_deg=12")}),
                 ConfigError);
    EXPECT_EQ(scene_key(cases[0]), "");  // material only: the base scene is shared
    EXPECT_NE(scene_key(cartesian_product({parse_sweep("volume=1e5")})[0]), "");
}

TEST(BatchSweep, TableRowsBecomeCases) {
    test::ScratchDir dir("batch-table");
    const auto table = dir.write("t.csv", "# comment\ndelta, phi_deg\n20,35\n\n25,30\n");
    const auto cases = read_case_table(table);
    ASSERT_EQ(cases.size(), 2u);
    EXPECT_EQ(cases[1].id, "delta=25_phi=30");
    EXPECT_THROW(read_case_table(dir.write("u.csv", "delta,grain\n20,1\n")), ConfigError);
    EXPECT_THROW(read_case_table(dir.write("r.csv", "delta,phi\n20\n")), InputError);
    EXPECT_THROW(read_case_table(dir.write("d.csv", "delta\n20\n20.0\n")), ConfigError);
}

TEST(BatchSweep, RestFacesTakesTrueOrFalseOverTheBase) {
    test::ScratchDir dir("batch-rest-faces");
    std::string toml = test::kCoarseParametricChute;
    toml.replace(toml.find("[numerics]\n"), 11, "[numerics]\nrest_faces = true\n");
    const Scenario base = assemble_scenario(dir.write("base.toml", toml), {});
    ASSERT_TRUE(base.numerics.rest_faces);
    const auto cases = cartesian_product({parse_sweep("rest_faces=false,true")});
    ASSERT_EQ(cases.size(), 2u);
    EXPECT_EQ(cases[0].id, "rest_faces=false");
    EXPECT_FALSE(scenario_for_case(base, cases[0]).numerics.rest_faces);
    EXPECT_TRUE(scenario_for_case(base, cases[1]).numerics.rest_faces);
    EXPECT_EQ(scene_key(cases[0]), "");  // numerics only: the base scene is shared
    const auto bad = cartesian_product({parse_sweep("rest_faces=yes")});
    try {
        scenario_for_case(base, bad[0]);
        ADD_FAILURE() << "rest_faces=yes accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scenario rest_faces=yes: rest_faces: expected true or false, got \"yes\"");
    }
}

TEST(BatchSweep, LimiterTakesTheWafLimitersOverTheBase) {
    test::ScratchDir dir("batch-limiter");
    const Scenario base = assemble_scenario(dir.write("base.toml", test::kCoarseParametricChute), {});
    ASSERT_EQ(base.numerics.limiter, Limiter::van_leer);
    const auto cases = cartesian_product({parse_sweep("limiter=superbee,minmod")});
    ASSERT_EQ(cases.size(), 2u);
    EXPECT_EQ(cases[0].id, "limiter=superbee");
    EXPECT_EQ(scenario_for_case(base, cases[0]).numerics.limiter, Limiter::superbee);
    EXPECT_EQ(scenario_for_case(base, cases[1]).numerics.limiter, Limiter::minmod);
    EXPECT_EQ(scene_key(cases[0]), "");  // numerics only: the base scene is shared
    ScenarioOverrides flags;
    flags.limiter = "van_albada";
    EXPECT_EQ(flags_replaced_by(cases[0], flags), (std::vector<std::string>{"--limiter"}));
    const auto bad = cartesian_product({parse_sweep("limiter=fast")});
    try {
        scenario_for_case(base, bad[0]);
        ADD_FAILURE() << "limiter=fast accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("scenario limiter=fast: --limiter: expected", 0), 0u)
            << e.what();
    }
}

TEST(BatchSweep, TheCasesValuesWinOverTheFlagsTheyReplace) {
    const auto cases = cartesian_product({parse_sweep("delta=20,25"), parse_sweep("thickness=1,2")});
    ScenarioOverrides flags;
    EXPECT_TRUE(flags_replaced_by(cases[0], flags).empty());
    flags.phi = 30.0;
    flags.volume = 1e4;
    flags.delta = 22.0;
    EXPECT_EQ(flags_replaced_by(cases[0], flags), (std::vector<std::string>{"--delta"}));
    flags.thickness = 3.0;
    EXPECT_EQ(flags_replaced_by(cases[0], flags),
              (std::vector<std::string>{"--delta", "--thickness"}));

    // The base scenario of the flags; the case's delta over the flag's.
    test::ScratchDir dir("batch-replaced");
    ScenarioOverrides chute_flags;
    chute_flags.delta = 22.0;
    chute_flags.phi = 30.0;
    const Scenario base =
        assemble_scenario(dir.write("base.toml", test::kCoarseParametricChute), chute_flags);
    EXPECT_EQ(base.material.delta_deg, 22.0);
    const auto deltas = cartesian_product({parse_sweep("delta=20,25")});
    EXPECT_EQ(scenario_for_case(base, deltas[1]).material.delta_deg, 25.0);
    EXPECT_EQ(scenario_for_case(base, deltas[1]).material.phi_deg, 30.0);
}

TEST(BatchSweep, CommandRefusesBadSweepsWithExitTwoAndWritesNothing) {
    test::ScratchDir dir("batch-refuse");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const std::string out = dir.file("out");
    for (const std::string spec : {"delta=1:x:2", "grain=3", "cell_size=0.5"}) {
        const auto r = test::run_binary(
            dir, "batch --scenario '" + base + "' --sweep '" + spec + "' --out '" + out + "'");
        EXPECT_EQ(r.exit_code, 2) << spec;
        EXPECT_NE(r.err.find("--sweep " + spec), std::string::npos) << r.err;
    }
    // A value the scenario refuses (delta > phi) names the scenario.
    const auto r = test::run_binary(
        dir, "batch --scenario '" + base + "' --sweep delta=20,40 --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("scenario delta=40"), std::string::npos) << r.err;
    // Neither --sweep nor --table.
    EXPECT_EQ(
        test::run_binary(dir, "batch --scenario '" + base + "' --out '" + out + "'").exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace avalanche
