#include "cli/arg_parser.hpp"

#include <cmath>
#include <sstream>

namespace cli {

namespace {

double parse_double(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value)) {
    throw ArgError("--" + option + ": '" + text + "' is not a finite number");
  }
  return value;
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
        const auto is_option = [](const char* a) {
          return a[0] == '-' && a[1] != '\0' && a[1] != '.' && (a[1] < '0' || a[1] > '9');
        };
        while (i + 1 < argc && !is_option(argv[i + 1])) {
          if (!value.empty()) value += ' ';
          value += argv[++i];
        }
        if (value.empty()) throw ArgError("--" + name + " needs a value");
      } else {
        if (i + 1 >= argc) throw ArgError("--" + name + " needs a value");
        value = argv[++i];
      }
      values_[name] = value;
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

int ArgParser::get_int(const std::string& name, int fallback) const {
  const auto value = get(name);
  if (!value) return fallback;
  const double d = parse_double(name, *value);
  if (d != std::floor(d) || std::abs(d) > 1e9) {
    throw ArgError("--" + name + ": '" + *value + "' is not an integer");
  }
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
  std::string text = *value;
  for (char& ch : text) {
    if (ch == ',') ch = ' ';
  }
  std::istringstream in(text);
  std::string token;
  while (in >> token) out.push_back(parse_double(name, token));
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
