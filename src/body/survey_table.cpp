#include "body/survey_table.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "util/file_read.hpp"

namespace body {

namespace {

constexpr std::size_t kMaxBytes = 64u << 20;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Splits one line at commas (no quoting).
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

std::string shown(const std::string& field) {
  if (field.size() <= 24) return "'" + field + "'";
  return "'" + field.substr(0, 24) + "...'";
}

}  // namespace

Eigen::Index SurveyTable::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), lower(name));
  if (it == columns.end()) throw std::out_of_range("survey column " + name + " was not read");
  return static_cast<Eigen::Index>(it - columns.begin());
}

SurveyTable read_survey_csv(const std::filesystem::path& path,
                            const std::vector<std::string>& columns) {
  const std::string name = path.string();
  std::string text;
  try {
    text = util::read_regular_file(path, kMaxBytes);
  } catch (const util::FileReadError& e) {
    throw std::runtime_error(e.what());
  }
  std::vector<std::string> lines;
  {
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines.push_back(std::move(line));
      start = end + 1;
    }
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();  // a final newline
  if (lines.empty()) throw std::runtime_error(name + ": empty (no header line)");
  if (text.find('"') != std::string::npos) {
    throw std::runtime_error(name + ": holds quoted fields, which this reader does not take");
  }
  std::vector<std::string> header = split(lines[0]);
  for (auto& h : header) h = lower(h);
  SurveyTable table;
  table.source = path;
  std::vector<std::size_t> index;
  for (const auto& wanted : columns) {
    const auto it = std::find(header.begin(), header.end(), lower(wanted));
    if (it == header.end()) {
      throw std::runtime_error(name + ": no column '" + wanted +
                               "' in the header (line 1): is this an ANSUR II file?");
    }
    table.columns.push_back(lower(wanted));
    index.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  const std::size_t rows = lines.size() - 1;
  if (rows == 0) throw std::runtime_error(name + ": a header and no rows");
  table.values.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t r = 0; r < rows; ++r) {
    const std::string where =
        name + ": row " + std::to_string(r + 1) + " (line " + std::to_string(r + 2) + ")";
    const auto fields = split(lines[r + 1]);
    if (fields.size() != header.size()) {
      throw std::runtime_error(where + " has " + std::to_string(fields.size()) +
                               " fields, the header " + std::to_string(header.size()) +
                               (fields.size() < header.size() ? " (a truncated file?)" : ""));
    }
    for (std::size_t c = 0; c < index.size(); ++c) {
      const std::string& field = fields[index[c]];
      const std::string at = where + ", column '" + columns[c] + "': ";
      if (field.empty()) throw std::runtime_error(at + "empty");
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(field.c_str(), &end);
      if (end != field.c_str() + field.size() || errno == ERANGE || !std::isfinite(v)) {
        throw std::runtime_error(at + shown(field) + " is not a number");
      }
      table.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = v;
    }
  }
  return table;
}

}  // namespace body
