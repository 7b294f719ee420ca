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

TEST_CASE("weighted distributions and correlations", "[survey]") {
  const std::vector<double> v{1.0, 2.0, 3.0, 4.0, 5.0};
  // Equal weights, whatever their size, give the plain statistics.
  const auto plain = body::distribution_of(v);
  const auto same = body::distribution_of(v, std::vector<double>(5, 0.2));
  CHECK(same.mean == Approx(plain.mean));
  CHECK(same.sd == Approx(plain.sd));
  CHECK(same.p5 == Approx(plain.p5));
  CHECK(same.p50 == Approx(plain.p50));
  CHECK(same.p95 == Approx(plain.p95));
  // Two groups weighed equally: three people at 1, 2, 3 and one at 10. The mean is the groups'
  // mean (2 and 10), the median from the three's largest up, and the SD wider than the three's
  // alone.
  const auto groups =
      body::distribution_of({1.0, 2.0, 3.0, 10.0}, {1.0 / 3, 1.0 / 3, 1.0 / 3, 1.0});
  CHECK(groups.count == 4);
  CHECK(groups.mean == Approx(6.0));
  CHECK(groups.p50 >= 3.0);
  CHECK(groups.p50 < 10.0);
  CHECK(groups.p5 >= 1.0);
  CHECK(groups.p95 <= 10.0);
  CHECK(groups.sd > body::distribution_of({1.0, 2.0, 3.0, 10.0}).sd);
  // A NaN is skipped with its weight; bad weights are refused.
  CHECK(body::distribution_of({1.0, std::nan(""), 3.0}, {1.0, 5.0, 1.0}).mean == Approx(2.0));
  CHECK_THROWS(body::distribution_of({1.0, 2.0}, {1.0, 0.0}));
  CHECK_THROWS(body::distribution_of({1.0, 2.0}, {1.0, std::nan("")}));
  CHECK_THROWS(body::distribution_of({1.0, 2.0}, {1.0}));
  // Correlations: equal weights give Pearson's r; the pairs that break the line weighed
  // almost nothing leave it nearly perfect.
  CHECK(body::correlation_of({1, 2, 3, 4}, {1, 3, 2, 4}, {2, 2, 2, 2}) == Approx(0.8));
  CHECK(body::correlation_of({1, 2, 3, 4, 5}, {1, 3, 2, 4, 5}, {1, 1e-9, 1e-9, 1, 1}) ==
        Approx(1.0).epsilon(1e-6));
  CHECK_THROWS(body::correlation_of({1, 2, 3}, {1, 2, 3}, {1, 1}));
  CHECK_THROWS(body::correlation_of({1, 2, 3}, {1, 2, 3}, {1, -1, 1}));
}

TEST_CASE("pooled survey tables weigh the same whatever their size", "[survey]") {
  // One person 1.60 m tall in one table, three at 1.90 m, 2.00 m and 2.10 m in the other:
  // pooled, the survey's mean height is the tables' mean, 1.80 m (the people's would be 1.90).
  const std::string head =
      "stature,weightkg,chestcircumference,waistcircumference,"
      "buttockcircumference,biacromialbreadth,crotchheight,acromionradialelength,"
      "radialestylionlength,neckcircumference,bideltoidbreadth,"
      "bicepscircumferenceflexed,thighcircumference,calfcircumference\n";
  const std::string rest = ",800,1000,900,1000,400,800,330,260,400,500,350,600,400\n";
  const auto one =
      body::read_survey_csv(write_csv("one.csv", head + "1600" + rest), body::survey_columns());
  const auto three = body::read_survey_csv(
      write_csv("three.csv", head + "1900" + rest + "2000" + rest + "2100" + rest),
      body::survey_columns());
  const auto model = body::load_builtin_model("neutral", 10);
  const auto c = body::compare_with_survey(model, {&one, &three}, 4, 3);
  CHECK(c.people == 4);
  REQUIRE(c.rows[0].name == "height");
  CHECK(c.rows[0].survey.mean == Approx(1.80));
  CHECK(c.rows[0].survey.count == 4);
  // Every other measure is the same for all four people.
  CHECK(c.rows[1].name == "mass");
  CHECK(c.rows[1].survey.mean == Approx(80.0));
  CHECK(c.rows[1].survey.sd == Approx(0.0).margin(1e-9));
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
