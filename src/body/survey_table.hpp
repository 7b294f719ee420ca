// An anthropometric survey table (the ANSUR II public CSV files): a header line of column
// names, then one person per line. Only the columns asked for are kept, as numbers; every
// problem (a missing file or column, a short row, a value that is not a number) is an error
// naming the file, the row and the column, so that a benchmark never averages garbage.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace body {

struct SurveyTable {
  std::filesystem::path source;
  std::vector<std::string> columns;  // as asked for, lower case
  Eigen::MatrixXd values;            // one row per person, one column per `columns` entry

  // The column index of `name` (lower case); throws std::out_of_range if it was not read.
  Eigen::Index column(const std::string& name) const;
};

// Reads `path` (a regular file of at most 64 MB) and keeps `columns` (matched without regard
// to case: the two ANSUR II files spell "subjectid" differently). Lines may end in CRLF; fields
// are plain (no quoting: the survey has none, and a quote is reported). Throws
// std::runtime_error "<file>: <problem>", e.g. "<file>: row 17 (line 18), column 'stature':
// 'abc' is not a number".
SurveyTable read_survey_csv(const std::filesystem::path& path,
                            const std::vector<std::string>& columns);

}  // namespace body
