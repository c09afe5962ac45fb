#include "engine/io/csv.hpp"

#include <charconv>
#include <fmt/format.h>
#include <set>
#include <string_view>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/text_lines.hpp"

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

// What is wrong with `field` as a number, or null when it is one (then stored in `value`).
// The whole field must be the number (locale-independent, unlike strtod).
const char* number_problem(std::string_view field, double& value) {
  // from_chars refuses a leading '+'; skip one, but only before a digit or a point ("+-1").
  const bool plus = field.size() > 1 && field[0] == '+' && field[1] != '-';
  const auto [end, ec] = std::from_chars(field.data() + plus, field.data() + field.size(), value);
  if (ec == std::errc::result_out_of_range) return "is out of the range of a double";
  if (field.empty() || ec != std::errc() || end != field.data() + field.size()) return "is not a number";
  return nullptr;
}

constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

}  // namespace

ParticleTable read_csv(const std::string& path) {
  TextLines lines(path, "the file");
  ParticleTable table;
  table.path = path;
  std::string text;
  std::string names;  // the header's names, for messages
  long header_line = 0;
  while (header_line == 0 && lines.next(text)) {  // the first line that is neither blank nor a comment
    const long line = lines.line();
    if (line == 1) {
      // Excel and Windows editors start UTF-8 files with a byte-order mark: not data.
      if (text.starts_with(kUtf8ByteOrderMark)) text.erase(0, kUtf8ByteOrderMark.size());
      // A UTF-16 file would only give baffling errors about its header.
      if (text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF"))
        lines.fail(line, "the file is UTF-16 text; save it as UTF-8 or ASCII");
    }
    const auto content = trim(text);
    if (content.empty() || content[0] == '#') continue;
    const auto fields = split(content);
    header_line = line;
    bool all_numbers = true;
    std::set<std::string_view> seen;  // a set: a header of many columns costs no quadratic search
    for (std::size_t k = 0; k < fields.size(); ++k) {
      std::string_view name = fields[k];
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
      if (name.empty()) lines.fail(line, fmt::format("column {} of the header has no name", k + 1));
      if (!seen.insert(name).second) lines.fail(line, fmt::format("column '{}' appears twice in the header", name));
      double ignored;
      all_numbers = all_numbers && !number_problem(name, ignored);
      table.columns.push_back(Column{std::string(name), 1, {}});
      names.append(k ? "," : "").append(name);
    }
    if (all_numbers)  // a file without a header would otherwise lose its first particle silently
      lines.fail(line, "the first line must be a header naming the columns (e.g. x,y,z,vx,vy,vz), not numbers");
    if (names.size() > 100) names = names.substr(0, 100) + "...";  // a message of a line, whatever the header
  }
  if (header_line == 0)
    throw Error(fmt::format("{}: empty file: expected a header line naming the columns", path), true);

  lines.share_rest();  // this process's rows (all of them in one process)
  while (lines.next(text)) {
    const auto content = trim(text);
    if (content.empty() || content[0] == '#') continue;
    const auto fields = split(content);
    if (fields.size() != table.columns.size())
      lines.fail(lines.line(),
                 fmt::format("expected {} fields ({}), found {}", table.columns.size(), names, fields.size()));
    for (std::size_t k = 0; k < fields.size(); ++k) {
      double v = 0;
      if (const char* problem = number_problem(fields[k], v))
        lines.fail(lines.line(),
                   fmt::format("column '{}': '{}' {}", table.columns[k].name, fields[k].substr(0, 40), problem));
      table.columns[k].values.push_back(v);
    }
    ++table.count;
  }
  table.first_row = static_cast<std::size_t>(lines.first_row());
  table.total = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(table.count)));
  if (table.total == 0)
    throw Error(fmt::format("{}: no data rows after the header on line {}", path, header_line), true);
  return table;
}

}  // namespace pbf
