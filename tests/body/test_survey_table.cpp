// The survey reader behind bench-survey: the columns asked for as numbers, and every broken
// file refused with the file, row and column named.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>

#include "body/model_loader.hpp"
#include "body/survey_comparison.hpp"
#include "body/survey_table.hpp"
#include "npz_fixtures.hpp"

namespace fs = std::filesystem;

namespace {

fs::path write_csv(const std::string& name, const std::string& text) {
  const fs::path path = fixtures::scratch_dir("survey") / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace

TEST_CASE("read_survey_csv keeps the columns asked for, whatever their case and line ends",
          "[survey]") {
  const auto path = write_csv("ok.csv",
                              "SubjectId,stature,weightkg,Gender\r\n"
                              "1,1650,612,Female\r\n"
                              "2,1702.5,700,Female\r\n");
  const auto t = body::read_survey_csv(path, {"subjectid", "Stature", "weightkg"});
  REQUIRE(t.values.rows() == 2);
  REQUIRE(t.values.cols() == 3);
  CHECK(t.values(1, t.column("stature")) == Approx(1702.5));
  CHECK(t.values(0, t.column("weightkg")) == Approx(612.0));
  CHECK_THROWS_AS(t.column("gender"), std::out_of_range);
}

TEST_CASE("read_survey_csv names the file, row and column of every problem", "[survey]") {
  const std::vector<std::string> cols = {"stature", "weightkg"};
  CHECK_THROWS_WITH(body::read_survey_csv(fixtures::scratch_dir("survey") / "missing.csv", cols),
                    Catch::Contains("missing.csv: no such file"));
  CHECK_THROWS_WITH(body::read_survey_csv(write_csv("empty.csv", ""), cols),
                    Catch::Contains("empty.csv: empty"));
  CHECK_THROWS_WITH(body::read_survey_csv(write_csv("header.csv", "stature,weightkg\n"), cols),
                    Catch::Contains("header.csv: a header and no rows"));
  CHECK_THROWS_WITH(body::read_survey_csv(write_csv("nocol.csv", "stature,mass\n1,2\n"), cols),
                    Catch::Contains("nocol.csv: no column 'weightkg' in the header"));
  // A file cut off in the middle of a row.
  CHECK_THROWS_WITH(
      body::read_survey_csv(write_csv("cut.csv", "id,stature,weightkg\n1,1650,612\n2,17"), cols),
      Catch::Contains("cut.csv: row 2 (line 3) has 2 fields, the header 3") &&
          Catch::Contains("truncated"));
  CHECK_THROWS_WITH(
      body::read_survey_csv(write_csv("text.csv", "id,stature,weightkg\n1,1650,612\n2,tall,70\n"),
                            cols),
      Catch::Contains("text.csv: row 2 (line 3), column 'stature': 'tall' is not a number"));
  CHECK_THROWS_WITH(
      body::read_survey_csv(write_csv("blank.csv", "id,stature,weightkg\n1,,612\n"), cols),
      Catch::Contains("row 1 (line 2), column 'stature': empty"));
  CHECK_THROWS_WITH(
      body::read_survey_csv(write_csv("nan.csv", "id,stature,weightkg\n1,nan,612\n"), cols),
      Catch::Contains("'nan' is not a number"));
  CHECK_THROWS_WITH(body::read_survey_csv("/dev/zero", cols), Catch::Contains("a device"));
}

TEST_CASE("distribution_of gives mean, SD and percentiles, skipping NaN", "[survey]") {
  const auto d = body::distribution_of({1.0, 2.0, 3.0, 4.0, 5.0, std::nan("")});
  CHECK(d.count == 5);
  CHECK(d.mean == Approx(3.0));
  CHECK(d.sd == Approx(std::sqrt(2.5)));
  CHECK(d.p50 == Approx(3.0));
  CHECK(d.p5 == Approx(1.2));
  CHECK(d.p95 == Approx(4.8));
  CHECK(std::isnan(body::distribution_of({}).mean));
}

TEST_CASE("a model's population is compared with the survey measure by measure", "[survey]") {
  // Two surveyed people 2.00 m and 2.10 m tall: the built-in model's bodies are shorter, so
  // the height gap is negative and large; every measure has a row.
  std::string csv =
      "stature,weightkg,chestcircumference,waistcircumference,"
      "buttockcircumference,biacromialbreadth,crotchheight,acromionradialelength,"
      "radialestylionlength,neckcircumference,bideltoidbreadth,"
      "bicepscircumferenceflexed,thighcircumference,calfcircumference\n";
  csv += "2000,1000,1000,900,1000,400,900,330,260,400,500,350,600,400\n";
  csv += "2100,1100,1100,950,1050,420,950,340,270,420,520,370,640,420\n";
  const auto table = body::read_survey_csv(write_csv("tall.csv", csv), body::survey_columns());
  const auto model = body::load_builtin_model("neutral", 10);
  const auto c = body::compare_with_survey(model, {&table}, 20, 3);
  CHECK(c.people == 2);
  CHECK(c.bodies == 20);
  REQUIRE(c.rows.size() == body::survey_measures().size());
  CHECK(c.rows[0].name == "height");
  CHECK(c.rows[0].survey.mean == Approx(2.05));
  CHECK(c.rows[0].model.mean > 1.4);
  CHECK(c.rows[0].model.mean < 1.9);
  CHECK(c.rows[0].mean_gap_sd < -3.0);
  CHECK(c.rows[2].name == "bmi");
  CHECK(c.rows[2].survey.mean == Approx((100.0 / 4.0 + 110.0 / 4.41) / 2.0));
  CHECK(c.rows[8].survey.mean == Approx(0.60));  // arm: acromion-radiale + radiale-stylion
  CHECK(c.rows[9].name == "neck");
  CHECK(c.rows[9].survey.mean == Approx(0.41));
  CHECK(c.rows[9].model.mean > 0.3);
  // Two people: every survey correlation is +-1 or undefined; the model's are computed over its
  // 20 bodies, and height with mass is strongly positive.
  REQUIRE_FALSE(c.correlations.empty());
  for (const auto& g : c.correlations) CHECK(g.a != g.b);
  bool height_mass = false;
  for (const auto& g : c.correlations) {
    if (g.a == "height" && g.b == "mass") {
      height_mass = true;
      CHECK(g.model > 0.3);
    }
  }
  CHECK(height_mass);
}

TEST_CASE("Pearson's correlation of two series", "[survey]") {
  CHECK(body::correlation_of({1, 2, 3, 4}, {2, 4, 6, 8}) == Approx(1.0));
  CHECK(body::correlation_of({1, 2, 3, 4}, {8, 6, 4, 2}) == Approx(-1.0));
  CHECK(body::correlation_of({1, 2, 3, 4}, {1, 3, 2, 4}) == Approx(0.8));
  CHECK(std::isnan(body::correlation_of({1, 2}, {1, 2})));
  CHECK(std::isnan(body::correlation_of({1, 1, 1}, {1, 2, 3})));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(body::correlation_of({1, 2, nan, 3, 4}, {2, 4, 5, 6, 8}) == Approx(1.0));
  CHECK_THROWS(body::correlation_of({1, 2, 3}, {1, 2}));
}
