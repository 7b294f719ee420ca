#include "cli/arg_parser.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "util/utf8.hpp"

namespace cli {

namespace {

// Plain decimal notation only: [+-]digits[.digits][e[+-]digits]. strtod alone would also take
// "0x10" (16), "inf", "nan" and "1e" prefixes, none of which a user means as a number here.
bool is_decimal_number(const std::string& t) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++i;
    return i - start;
  };
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < t.size() && t[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == t.size();
}

double parse_double(const std::string& option, const std::string& text) {
  if (!is_decimal_number(text)) {
    throw ArgError("--" + option + ": '" + text + "' is not a number (write it like 1.5 or -2e-3)");
  }
  errno = 0;
  const double value = std::strtod(text.c_str(), nullptr);
  // Underflow (1e-320) is a legal tiny number; only overflow is out of range.
  if (!std::isfinite(value)) {
    throw ArgError("--" + option + ": '" + text + "' is too large (beyond double precision)");
  }
  return value;
}

// An argument that starts with '-' is a value, not an option, when it reads as a number
// ("-1.5", "-.5", "-inf"): then a bad number gets the number's error, not "needs a value".
bool looks_like_option(const char* a) {
  if (a[0] != '-' || a[1] == '\0') return false;
  if (a[1] == '.' || (a[1] >= '0' && a[1] <= '9')) return false;
  const std::string rest(a + 1);
  for (const char* word : {"inf", "infinity", "nan"}) {
    if (rest.size() == std::string(word).size() &&
        std::equal(rest.begin(), rest.end(), word, [](char x, char y) {
          return std::tolower(static_cast<unsigned char>(x)) == y;
        })) {
      return false;
    }
  }
  return true;
}

}  // namespace

ArgParser::ArgParser(int argc, char** argv, std::set<std::string> flags,
                     std::set<std::string> multi) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      std::string name = arg.substr(2);
      std::string value;
      const auto eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      } else if (flags.count(name) != 0 || name == "help") {
        value = "1";
      } else if (multi.count(name) != 0) {
        // Consume until the next option; negative numbers ("-1.5") are values, not options.
        // Stop at the next option ("--x", "-o", "-h"); "-1.5" and "-.5" are values.
        while (i + 1 < argc && !looks_like_option(argv[i + 1])) {
          if (!value.empty()) value += ' ';
          value += argv[++i];
        }
        if (value.empty()) throw ArgError("--" + name + " needs a value");
      } else {
        if (i + 1 >= argc) throw ArgError("--" + name + " needs a value");
        value = argv[++i];
      }
      values_[name] = value;
      all_[name].push_back(value);
    } else if (arg == "-o") {
      if (i + 1 >= argc) throw ArgError("-o needs a file name");
      values_["output"] = argv[++i];
    } else if (arg == "-h") {
      values_["help"] = "1";
    } else {
      positional_.push_back(arg);
    }
  }
}

bool ArgParser::has(const std::string& name) const {
  return values_.count(name) != 0;
}

std::vector<std::string> ArgParser::get_all(const std::string& name) const {
  const auto it = all_.find(name);
  return it == all_.end() ? std::vector<std::string>{} : it->second;
}

std::optional<std::string> ArgParser::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string ArgParser::get_or(const std::string& name, const std::string& fallback) const {
  return get(name).value_or(fallback);
}

std::string ArgParser::require(const std::string& name) const {
  const auto value = get(name);
  if (!value) throw ArgError("missing required option --" + name);
  return *value;
}

std::string ArgParser::get_text(const std::string& name, const std::string& fallback) const {
  const std::string value = get_or(name, fallback);
  if (!util::is_valid_utf8(value)) {
    throw ArgError("--" + name + ": the text is not valid UTF-8 (check the terminal's encoding)");
  }
  return value;
}

int ArgParser::get_int(const std::string& name, int fallback) const {
  const auto value = get(name);
  if (!value) return fallback;
  const double d = parse_double(name, *value);
  if (d != std::floor(d)) throw ArgError("--" + name + ": '" + *value + "' is not an integer");
  if (std::abs(d) > 1e9) throw ArgError("--" + name + ": '" + *value + "' is out of range");
  return static_cast<int>(d);
}

double ArgParser::get_double(const std::string& name, double fallback) const {
  const auto value = get(name);
  return value ? parse_double(name, *value) : fallback;
}

std::vector<double> ArgParser::get_doubles(const std::string& name) const {
  std::vector<double> out;
  const auto value = get(name);
  if (!value) return out;
  // Values are separated by commas and/or spaces; an empty field ("1,,2", "1,") is an error,
  // not silently skipped.
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = value->find(',', start);
    std::istringstream field(
        value->substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    std::string token;
    int tokens = 0;
    while (field >> token) {
      out.push_back(parse_double(name, token));
      ++tokens;
    }
    if (tokens == 0 && value->find(',') != std::string::npos) {
      throw ArgError("--" + name + ": empty value between commas in '" + *value + "'");
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

void ArgParser::reject_unknown(const std::set<std::string>& known) const {
  for (const auto& [name, value] : values_) {
    if (known.count(name) == 0 && name != "help") {
      throw ArgError("unknown option --" + name + " (see --help)");
    }
  }
}

}  // namespace cli
