#include "engine/io/csv.hpp"

#include <charconv>
#include <fmt/format.h>
#include <fstream>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  while (true) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

// The whole field must be the number (locale-independent, unlike strtod).
bool parse_number(std::string_view field, double& value) {
  const char* begin = field.data() + (field.size() > 1 && field[0] == '+' ? 1 : 0);  // from_chars refuses '+'
  const auto [end, ec] = std::from_chars(begin, field.data() + field.size(), value);
  return !field.empty() && ec == std::errc() && end == field.data() + field.size();
}

}  // namespace

ParticleTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot open the file", path), true);
  auto fail = [&](long line, const std::string& message) {
    throw Error(fmt::format("{}:{}: {}", path, line, message), true);
  };

  ParticleTable table;
  table.path = path;
  std::string text;
  std::string names;  // the header's names, for messages
  long line = 0, header_line = 0;
  while (std::getline(in, text)) {
    ++line;
    const auto content = trim(text);
    if (content.empty() || content[0] == '#') continue;
    const auto fields = split(content);

    if (header_line == 0) {  // the first line that is neither blank nor a comment
      header_line = line;
      bool all_numbers = true;
      for (std::size_t k = 0; k < fields.size(); ++k) {
        std::string_view name = fields[k];
        if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
        if (name.empty()) fail(line, fmt::format("column {} of the header has no name", k + 1));
        if (table.find(std::string(name))) fail(line, fmt::format("column '{}' appears twice in the header", name));
        double ignored;
        all_numbers = all_numbers && parse_number(name, ignored);
        table.columns.push_back(Column{std::string(name), 1, {}});
        names.append(k ? "," : "").append(name);
      }
      if (all_numbers)  // a file without a header would otherwise lose its first particle silently
        fail(line, "the first line must be a header naming the columns (e.g. x,y,z,vx,vy,vz), not numbers");
      continue;
    }

    if (fields.size() != table.columns.size())
      fail(line, fmt::format("expected {} fields ({}), found {}", table.columns.size(), names, fields.size()));
    for (std::size_t k = 0; k < fields.size(); ++k) {
      double v = 0;
      if (!parse_number(fields[k], v))
        fail(line, fmt::format("column '{}': '{}' is not a number", table.columns[k].name, fields[k].substr(0, 40)));
      table.columns[k].values.push_back(v);
    }
    ++table.count;
  }
  if (in.bad()) throw Error(fmt::format("{}: cannot read the file", path), true);
  if (header_line == 0)
    throw Error(fmt::format("{}: empty file: expected a header line naming the columns", path), true);
  if (table.count == 0)
    throw Error(fmt::format("{}: no data rows after the header on line {}", path, header_line), true);
  return table;
}

}  // namespace pbf
