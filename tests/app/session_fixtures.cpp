#include "session_fixtures.hpp"

#include <functional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/session.hpp"

namespace test_fixtures {

using nlohmann::json;

std::string good_session_json() {
  app::SessionSettings settings;
  settings.components = 4;
  settings.seed = 11;
  app::Session session(settings);
  // The search with a small model window, restored from the session's own fresh state.
  json search = json::parse(session.search().to_json());
  search["options"]["model"]["max_points"] = 24;
  sps::PlaneSearch current = sps::PlaneSearch::from_json(search.dump());
  const std::vector<std::vector<sps::GridCell>> planes{{{0, 0}, {1, 1}, {2, 1}, {1, 0}},
                                                       {{2, 2}, {0, 1}, {1, 1}, {2, 0}},
                                                       {{1, 2}, {1, 1}, {0, 0}, {2, 2}}};
  for (const auto& clicks : planes) {
    for (const auto& c : clicks) session.click(c);
    const app::Submission sub = session.submission();
    current.submit(sub.chosen, sub.extra_comparisons);
    session.finish_plane(current);
  }
  session.click({1, 1});
  return session.to_json();
}

std::vector<SessionFixture> broken_session_fixtures() {
  const json good = json::parse(good_session_json());
  std::vector<SessionFixture> out;
  const auto add = [&](const std::string& name, const std::string& expected,
                       const std::function<void(json&)>& change) {
    json j = good;
    change(j);
    out.push_back({name, j.dump(1), expected});
  };
  // Defect 1: a snapshot whose preferences point past its points, with more points than the
  // model window (the window code indexed out of bounds).
  add("history-preferences-past-points", "pointing past",
      [](json& j) { j["search"]["history"][1]["points"] = 25; });
  // Defect 2: absurd numbers that used to size allocations or overflow int conversions.
  add("components-1e9", "components", [](json& j) { j["settings"]["components"] = 1000000000; });
  add("components-1e300", "components", [](json& j) { j["settings"]["components"] = 1e300; });
  add("dims-1e9", "dims", [](json& j) { j["search"]["options"]["dims"] = 1000000000; });
  add("grid-1e300", "grid_size", [](json& j) { j["settings"]["grid_size"] = 1e300; });
  add("max-points-huge", "max_points",
      [](json& j) { j["search"]["options"]["model"]["max_points"] = 4000000000.0; });
  add("threads-negative", "threads", [](json& j) { j["search"]["options"]["threads"] = -3; });
  add("btl-scale-zero", "btl_scale",
      [](json& j) { j["search"]["options"]["model"]["btl_scale"] = 0.0; });
  add("preference-index-out-of-range", "preference index",
      [](json& j) { j["search"]["preferences"][0]["chosen"] = 99999; });
  add("preference-repeats-point", "repeats", [](json& j) {
    j["search"]["preferences"][0]["others"][0] = j["search"]["preferences"][0]["chosen"];
  });
  // Defect 3: a history entry whose random-generator state cannot be restored by undo.
  add("history-rng-unreadable", "random generator state is unreadable",
      [](json& j) { j["search"]["history"][0]["rng"] = "not a generator state"; });
  // Defect 4: a kernel amplitude that overflows every later value into NaN.
  add("amplitude-1e300", "amplitude", [](json& j) { j["search"]["params"]["amplitude"] = 1e300; });
  add("history-amplitude-1e300", "amplitude",
      [](json& j) { j["search"]["history"][2]["params"]["amplitude"] = 1e300; });
  add("latent-null", "non-number", [](json& j) { j["search"]["latent"][0] = nullptr; });
  add("latent-wrong-length", "entries, expected",
      [](json& j) { j["search"]["latent"].push_back(0.5); });
  add("history-out-of-order", "out of order",
      [](json& j) { std::swap(j["search"]["history"][0], j["search"]["history"][2]); });
  add("plane-outside-box", "plane.c", [](json& j) { j["search"]["plane"]["c"][0] = 7.5; });
  add("history-length-mismatch", "history length",
      [](json& j) { j["history"].erase(j["history"].begin()); });
  add("path-cell-outside-grid", "path", [](json& j) { j["path"][0] = json::array({7, 0}); });
  // A finished plane's path has at most one click per zoom level (fewer when it ended early,
  // none when the point was set with the expert sliders); more is damage.
  add("history-path-too-long", "history path has 5 clicks", [](json& j) {
    j["history"][0]["path"].push_back(json::array({1, 1}));
  });
  add("start-point-string", "start_point", [](json& j) { j["start_point"][0] = "half"; });
  // Holds are optional; when present, each a name and a positive value.
  add("holds-not-array", "holds must be an array", [](json& j) { j["holds"] = "height"; });
  add("holds-value-string", "holds entries", [](json& j) {
    j["holds"] = json::array({{{"name", "height"}, {"value", "tall"}}});
  });
  add("holds-value-negative", "holds value of height", [](json& j) {
    j["holds"] = json::array({{{"name", "height"}, {"value", -1.8}}});
  });
  add("holds-name-empty", "holds has a name", [](json& j) {
    j["holds"] = json::array({{{"name", ""}, {"value", 1.8}}});
  });
  add("wrong-format", "not a sequential-gallery session",
      [](json& j) { j["format"] = "something else"; });
  const std::string text = good.dump(1);
  // Values nested 100,000 deep (the serializer that echoed them into the message recursed
  // until the stack ran out) and a text far longer than any field holds. Built as text: a tree
  // that deep is what must never be built.
  const auto deep = [](const std::string& inner) {
    constexpr int kDepth = 100000;
    return std::string(kDepth, '[') + inner + std::string(kDepth, ']');
  };
  const auto replace_first = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    if (at == std::string::npos) throw std::logic_error("fixture text lacks " + from);
    return t.replace(at, from.size(), to);
  };
  out.push_back({"deep-version", replace_first("\"version\": 1", "\"version\": " + deep("1")),
                 "nested more than"});
  out.push_back({"deep-components",
                 replace_first("\"components\": 4", "\"components\": " + deep("4")),
                 "nested more than"});
  out.push_back({"deep-search",
                 replace_first("\"search\": {", "\"search\": {\"deep\": " + deep("") + ","),
                 "nested more than"});
  out.push_back({"model-path-huge",
                 replace_first("\"model_path\": \"\"",
                               "\"model_path\": \"" + std::string(300000, 'a') + "\""),
                 "longer than"});
  add("model-path-long", "settings.model_path is a text of 5000 bytes",
      [](json& j) { j["settings"]["model_path"] = std::string(5000, 'b'); });
  add("space-null", "settings.space must be text, found null",
      [](json& j) { j["settings"]["space"] = nullptr; });
  add("population-mean-without-sd", "population_mean is given without population_sd", [](json& j) {
    j["search"]["options"]["population_mean"] = json::array({0.5, 0.5, 0.5, 0.5});
    j["search"]["options"].erase("population_sd");
  });
  out.push_back({"truncated", text.substr(0, text.size() / 2), "not valid JSON"});
  out.push_back({"empty", "", "not valid JSON"});
  out.push_back({"top-level-array", "[1, 2, 3]", "not a sequential-gallery session"});
  return out;
}

}  // namespace test_fixtures
