// Session files for tests: a real session made through the API, and broken variants of it,
// each with the words its error message must contain. Used by app_tests (Session::from_json)
// and, written to files by session_fixture_writer, by the session-info CLI test.
#pragma once

#include <string>
#include <vector>

namespace test_fixtures {

struct SessionFixture {
  std::string name;      // file stem, e.g. "history-preferences-past-points"
  std::string text;      // the file's content
  std::string expected;  // words the error must contain ("" for a good session)
};

// A valid session: 4 components, 3 finished planes, 1 click on the current plane, and a model
// window (max_points 24) smaller than its points, so that the window slides.
std::string good_session_json();

// Defects users met in session files, and other attacks; each must be refused with `expected`.
std::vector<SessionFixture> broken_session_fixtures();

}  // namespace test_fixtures
