// Stored JSON is bounded before a tree is built from it, and values in messages are short.
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sps/json_fields.hpp"

namespace jf = sps::json_fields;

TEST_CASE("parse_bounded refuses deep nesting, long texts and large inputs before parsing",
          "[json]") {
  CHECK(jf::parse_bounded("{\"a\": [1, 2, {\"b\": \"x\"}]}").at("a").size() == 3);
  // 100,000 levels: the tree (and anything walking it recursively) is never built.
  const std::string deep =
      "{\"version\": " + std::string(100000, '[') + "1" + std::string(100000, ']') + "}";
  CHECK_THROWS_WITH(jf::parse_bounded(deep), Catch::Contains("nested more than 64 levels deep") &&
                                                 Catch::Contains("at byte 75"));
  // Brackets inside strings are text, not nesting; escaped quotes do not end a string.
  const std::string brackets = "{\"s\": \"" + std::string(1000, '[') + "\\\"]\"}";
  CHECK(jf::parse_bounded(brackets).at("s").get<std::string>().size() == 1002);
  jf::JsonLimits small;
  small.max_string_bytes = 16;
  CHECK_THROWS_WITH(jf::parse_bounded("{\"path\": \"" + std::string(100, 'a') + "\"}", small),
                    Catch::Contains("longer than 16 bytes"));
  small.max_bytes = 10;
  CHECK_THROWS_WITH(jf::parse_bounded(std::string(11, ' '), small), Catch::Contains("too large"));
  CHECK_THROWS_WITH(jf::parse_bounded("{\"a\": "), Catch::Contains("not valid JSON"));
}

TEST_CASE("brief describes any value in a few words", "[json]") {
  CHECK(jf::brief(nlohmann::json(3)) == "3");
  CHECK(jf::brief(nlohmann::json(nullptr)) == "null");
  CHECK(jf::brief(nlohmann::json("body")) == "\"body\"");
  CHECK(jf::brief(nlohmann::json(std::string(100000000, 'x'))) == "a text of 100000000 bytes");
  nlohmann::json nested = nlohmann::json::array({1, 2, 3});
  CHECK(jf::brief(nested) == "an array of 3 values");
  CHECK(jf::brief(nlohmann::json::object()) == "an object of 0 fields");
  // The number checks name the field and describe the value briefly.
  CHECK_THROWS_WITH(jf::integer(nlohmann::json(std::string(5000, 'y')), "components", 1, 40),
                    Catch::Contains("components must be an integer, found a text of 5000 bytes"));
}

TEST_CASE("field and text name what is missing or of the wrong kind", "[json]") {
  const auto j = nlohmann::json::parse(R"({"space": null, "model_path": "m.npz"})");
  CHECK(jf::text(j, "model_path", "settings.model_path") == "m.npz");
  CHECK_THROWS_WITH(jf::text(j, "space", "settings.space"),
                    Catch::Equals("settings.space must be text, found null"));
  CHECK_THROWS_WITH(jf::field(j, "seed", "settings.seed"),
                    Catch::Equals("settings.seed is missing"));
  CHECK_THROWS_WITH(jf::text(j, "model_path", "settings.model_path", 3),
                    Catch::Contains("is a text of 5 bytes, at most 3"));
}
