// A small option parser shared by the subcommands: `--name value`, `--name=value`, flags,
// and comma- or space-separated number lists, with errors a user can act on.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

class ArgError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ArgParser {
 public:
  // `flags` take no value; every other `--name` consumes the next argument (or `=value`).
  // Values of options listed in `multi` may span several arguments until the next `--x`.
  ArgParser(int argc, char** argv, std::set<std::string> flags, std::set<std::string> multi = {});

  bool has(const std::string& name) const;
  std::optional<std::string> get(const std::string& name) const;  // the last one given
  // Every value of a repeatable option, in order (--target height=1.8 --target mass=85).
  std::vector<std::string> get_all(const std::string& name) const;
  std::string get_or(const std::string& name, const std::string& fallback) const;
  std::string require(const std::string& name) const;
  // A value that is free text (a name, not a path): must be valid UTF-8, since it ends up in
  // JSON; throws ArgError otherwise.
  std::string get_text(const std::string& name, const std::string& fallback) const;
  int get_int(const std::string& name, int fallback) const;
  double get_double(const std::string& name, double fallback) const;
  std::vector<double> get_doubles(const std::string& name) const;  // "1,2 3" -> {1,2,3}
  const std::vector<std::string>& positional() const { return positional_; }

  // Throws ArgError naming the first option not in `known`.
  void reject_unknown(const std::set<std::string>& known) const;

 private:
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> all_;
  std::vector<std::string> positional_;
};

}  // namespace cli
