#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/arg_parser.hpp"

namespace {

cli::ArgParser parse(std::vector<std::string> words, std::set<std::string> flags = {},
                     std::set<std::string> multi = {}) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  return cli::ArgParser(static_cast<int>(argv.size()), argv.data(), std::move(flags),
                        std::move(multi));
}

}  // namespace

TEST_CASE("options, flags and values", "[cli]") {
  const auto a = parse({"cmd", "--dims", "5", "--quiet", "--method=sls", "extra"}, {"quiet"});
  CHECK(a.get_int("dims", 0) == 5);
  CHECK(a.has("quiet"));
  CHECK(a.get_or("method", "") == "sls");
  CHECK(a.positional() == std::vector<std::string>{"extra"});
  CHECK(a.get_double("missing", 2.5) == 2.5);
}

TEST_CASE("the --help option is always a flag, whatever the command declares", "[cli]") {
  const auto a = parse({"cmd", "--help", "--dims", "3"});
  CHECK(a.has("help"));
  CHECK(a.get_int("dims", 0) == 3);
}

TEST_CASE("multi-value options take negative numbers and stop at -o", "[cli]") {
  const auto a = parse({"cmd", "--betas", "1.5", "-2", "-.5,3", "-o", "out.glb", "--x", "0.1"}, {},
                       {"betas", "x"});
  CHECK(a.get_doubles("betas") == std::vector<double>{1.5, -2.0, -0.5, 3.0});
  CHECK(a.get_or("output", "") == "out.glb");
  CHECK(a.get_doubles("x") == std::vector<double>{0.1});
}

TEST_CASE("bad values are reported with the option name", "[cli]") {
  CHECK_THROWS_WITH(parse({"cmd", "--dims", "five"}).get_int("dims", 1),
                    Catch::Contains("--dims") && Catch::Contains("five"));
  CHECK_THROWS_WITH(parse({"cmd", "--dims", "2.5"}).get_int("dims", 1), Catch::Contains("integer"));
  CHECK_THROWS_WITH(parse({"cmd", "--x", "nan"}).get_double("x", 1),
                    Catch::Contains("not a number"));
  CHECK_THROWS_AS(parse({"cmd", "--dims"}), cli::ArgError);
  CHECK_THROWS_WITH(parse({"cmd", "--bogus", "1"}).reject_unknown({"dims"}),
                    Catch::Contains("--bogus"));
  CHECK_THROWS_WITH(parse({"cmd"}).require("model"), Catch::Contains("--model"));
}

TEST_CASE("numbers users actually typed get the right message", "[cli]") {
  // "-inf" is a (bad) value of --betas, not a missing value.
  CHECK_THROWS_WITH(parse({"cmd", "--betas", "-inf"}, {}, {"betas"}).get_doubles("betas"),
                    Catch::Contains("'-inf' is not a number"));
  CHECK_THROWS_WITH(parse({"cmd", "--betas", "1", "-Infinity"}, {}, {"betas"}).get_doubles("betas"),
                    Catch::Contains("'-Infinity' is not a number"));
  // A tiny number underflows to (almost) zero: legal. A huge one is "too large".
  const auto tiny = parse({"cmd", "--x", "1e-320"}).get_double("x", 1);
  CHECK(tiny >= 0.0);
  CHECK(tiny < 1e-300);
  CHECK_THROWS_WITH(parse({"cmd", "--x", "1e400"}).get_double("x", 1),
                    Catch::Contains("too large"));
  // Empty fields and hexadecimal are errors, not [1, 2] and 16.
  CHECK_THROWS_WITH(parse({"cmd", "--betas", "1,,2"}, {}, {"betas"}).get_doubles("betas"),
                    Catch::Contains("empty value"));
  CHECK_THROWS_WITH(parse({"cmd", "--betas", "1,"}, {}, {"betas"}).get_doubles("betas"),
                    Catch::Contains("empty value"));
  CHECK_THROWS_WITH(parse({"cmd", "--dims", "0x10"}).get_int("dims", 1),
                    Catch::Contains("'0x10' is not a number"));
  CHECK_THROWS_WITH(parse({"cmd", "--dims", "1e12"}).get_int("dims", 1),
                    Catch::Contains("out of range"));
  // Still fine: spaces around commas, exponents, signs.
  CHECK(parse({"cmd", "--betas", "1 ,2", "+3e0", "-.5"}, {}, {"betas"}).get_doubles("betas") ==
        std::vector<double>{1.0, 2.0, 3.0, -0.5});
}
