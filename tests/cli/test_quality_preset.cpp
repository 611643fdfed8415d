// `--quality draft|standard|fine`: what each preset sets, that explicit flags win,
// and that the automatic (DEM-resolution) cell size is scaled when the DEM is read.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/quality_preset.hpp"
#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

TEST(QualityPreset, StandardIsTheDefaultNumerics) {
    // The standard preset must be exactly what a run without --quality does, or the
    // stated error and cost of "standard" in docs/performance.md would not be the
    // default's.
    const QualityPreset p = quality_preset(Quality::standard);
    const NumericsParams n;
    EXPECT_EQ(p.scheme, n.scheme);
    EXPECT_EQ(p.limiter, n.limiter);
    EXPECT_EQ(p.cfl, n.cfl);
    EXPECT_EQ(p.splitting, n.splitting);
    EXPECT_EQ(p.cell_size_factor, 1.0);
}

TEST(QualityPreset, PresetsOrderCostDraftBelowStandardBelowFine) {
    // Cost per simulated second scales as advections per step / (dx^3 C) in 2D (cells
    // x steps x advections; L S L advects twice per step, S L S once): a draft must be
    // cheaper than standard, fine dearer.
    auto cost = [](const QualityPreset& p) {
        const double advections = p.splitting == Splitting::lsl ? 2.0 : 1.0;
        return advections /
               (p.cell_size_factor * p.cell_size_factor * p.cell_size_factor * p.cfl);
    };
    EXPECT_LT(cost(quality_preset(Quality::draft)), cost(quality_preset(Quality::standard)));
    EXPECT_GT(cost(quality_preset(Quality::fine)), cost(quality_preset(Quality::standard)));
    for (Quality q : {Quality::draft, Quality::standard, Quality::fine}) {
        EXPECT_LE(quality_preset(q).cfl, 0.5);  // the stability limit of the scheme
        EXPECT_EQ(parse_quality(to_string(q), "--quality"), q);
    }
}

TEST(QualityPreset, ScalesTheScenarioCellSizeAndExplicitFlagsWin) {
    test::ScratchDir dir("quality");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);  // cell_size 0.5
    ScenarioOverrides o;
    o.quality = "draft";
    const QualityPreset draft = quality_preset(Quality::draft);
    Scenario s = assemble_scenario(file, o);
    EXPECT_EQ(s.cell_size, 0.5 * draft.cell_size_factor);
    EXPECT_EQ(s.numerics.cfl, draft.cfl);
    EXPECT_EQ(s.numerics.scheme, draft.scheme);
    EXPECT_EQ(s.numerics.splitting, draft.splitting);

    o.cfl = 0.15;
    o.cell_size = 0.25;
    o.scheme = "godunov";
    s = assemble_scenario(file, o);
    EXPECT_EQ(s.numerics.cfl, 0.15);
    EXPECT_EQ(s.cell_size, 0.25);
    EXPECT_EQ(s.numerics.scheme, Scheme::godunov);
    EXPECT_EQ(s.cell_size_factor, 1.0);
}

TEST(QualityPreset, UnknownPresetIsRefusedNamingTheFlag) {
    test::ScratchDir dir("quality_bad");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    ScenarioOverrides o;
    o.quality = "ultra";
    try {
        (void)assemble_scenario(file, o);
        FAIL() << "accepted --quality ultra";
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("--quality: expected draft, standard or fine", 0), 0u) << e.what();
    }
}

TEST(QualityPreset, DraftDoublesTheAutomaticDemCellSize) {
    // Draft on an automatic cell size must give cells of twice the DEM's pixel size
    // (read from its geotransform here, about 5 m), and must change the config hash.
    ScenarioOverrides o;
    o.dem = {test::avaKot("avaKot_dem.tif")};
    o.release = test::avaKot("avaKot_release.gpkg");
    Scenario standard = assemble_scenario(std::nullopt, o);
    o.quality = "draft";
    Scenario draft = assemble_scenario(std::nullopt, o);
    EXPECT_EQ(draft.cell_size, 0.0);
    EXPECT_EQ(draft.cell_size_factor, quality_preset(Quality::draft).cell_size_factor);
    EXPECT_NE(config_hash(effective_config(standard)), config_hash(effective_config(draft)));
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(o.dem[0].c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_TRUE(ds);
    double gt[6];
    ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
    const PreparedScene scene = prepare_scene(draft);
    EXPECT_DOUBLE_EQ(scene.grid.dx, gt[1] * draft.cell_size_factor);
    EXPECT_DOUBLE_EQ(scene.grid.dy, -gt[5] * draft.cell_size_factor);
}

TEST(QualityPreset, ResumeRebuildsTheScaledDemCellSize) {
    // --resume rebuilds the scenario from the recorded effective configuration: the
    // preset's factor on an automatic cell size must survive that round trip, with the
    // same configuration hash (which the resume compares).
    ScenarioOverrides o;
    o.dem = {test::avaKot("avaKot_dem.tif")};
    o.release = test::avaKot("avaKot_release.gpkg");
    o.quality = "draft";
    const Scenario draft = assemble_scenario(std::nullopt, o);
    const Scenario back = scenario_from_config(effective_config(draft), "checkpoint.h5");
    EXPECT_EQ(back.cell_size_factor, draft.cell_size_factor);
    EXPECT_EQ(config_hash(effective_config(back)), config_hash(effective_config(draft)));
}

}  // namespace
}  // namespace avalanche
