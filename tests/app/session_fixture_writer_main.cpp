// Writes the session fixtures into a folder: good.json and <name>.json for each broken one,
// with <name>.expected holding the words its error must contain (for session_info_test.sh).
#include <fstream>
#include <iostream>
#include <string>

#include "session_fixtures.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: session_fixture_writer FOLDER\n";
    return 2;
  }
  const std::string dir = argv[1];
  std::ofstream(dir + "/good.json", std::ios::binary) << test_fixtures::good_session_json();
  for (const auto& f : test_fixtures::broken_session_fixtures()) {
    std::ofstream(dir + "/" + f.name + ".json", std::ios::binary) << f.text;
    std::ofstream(dir + "/" + f.name + ".expected", std::ios::binary) << f.expected;
  }
  return 0;
}
