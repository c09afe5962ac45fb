#include "engine/registry/style_registry.hpp"

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"

namespace pbf {

namespace {
const char* kind_name(StyleKind kind) { return kind == StyleKind::fix ? "fix" : "compute"; }
}  // namespace

const StyleRegistry& StyleRegistry::builtin() {
  static const StyleRegistry registry = [] {
    StyleRegistry r;
    register_builtin_styles(r);
    return r;
  }();
  return registry;
}

void StyleRegistry::add(StyleInfo info) {
  if (find(info.name)) throw Error(fmt::format("style '{}' registered twice", info.name));
  styles_.push_back(std::move(info));
}

const StyleInfo* StyleRegistry::find(const std::string& name) const {
  for (const auto& s : styles_)
    if (s.name == name) return &s;
  return nullptr;
}

const StyleInfo& StyleRegistry::require(const std::string& style, StyleKind kind) const {
  const StyleInfo* info = find(style);
  if (!info || info->kind != kind) {
    std::vector<std::string> valid;
    for (const auto& s : styles_)
      if (s.kind == kind) valid.push_back(s.name);
    throw Error(fmt::format("unknown {} style '{}'{}; valid {} styles: {}", kind_name(kind), style,
                            did_you_mean(style, valid), kind_name(kind), fmt::join(valid, ", ")));
  }
  return *info;
}

std::unique_ptr<Fix> StyleRegistry::make_fix(const std::string& id, const std::string& style,
                                             const GivenParams& given) const {
  const StyleInfo& info = require(style, StyleKind::fix);
  const std::string what = fmt::format("fix '{}' ({})", id, style);
  Params params(what, info.params, given);
  try {
    return info.make_fix(id, params);
  } catch (const MissingFile& e) {  // kept apart: the command line says more of it
    throw MissingFile(fmt::format("{}: {}", what, e.what()), e.path());
  } catch (const Error& e) {  // range checks in the constructor
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
}

std::unique_ptr<Compute> StyleRegistry::make_compute(const std::string& id, const std::string& style,
                                                     const GivenParams& given) const {
  const StyleInfo& info = require(style, StyleKind::compute);
  const std::string what = fmt::format("compute '{}' ({})", id, style);
  Params params(what, info.params, given);
  try {
    return info.make_compute(id, params);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
}

std::string StyleRegistry::help() const {
  std::string out = "Styles (pbfengine help STYLE lists a style's parameters):\n";
  for (StyleKind kind : {StyleKind::fix, StyleKind::compute})
    for (const auto& s : styles_)
      if (s.kind == kind) out += fmt::format("  {:<8} {:<16} {}\n", kind_name(kind), s.name, s.summary);
  return out;
}

std::string StyleRegistry::help(const std::string& style) const {
  const StyleInfo* info = find(style);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& s : styles_) names.push_back(s.name);
    throw Error(fmt::format("unknown style '{}'{}; 'pbfengine help' lists them", style, did_you_mean(style, names)));
  }
  std::string out = fmt::format("{} {}: {}\n", kind_name(info->kind), info->name, info->summary);
  if (!info->values.empty()) {
    std::string values = info->values;
    std::erase(values, '`');
    out += fmt::format("Values: {}\n", values);
  }
  if (info->params.empty()) return out + "  (no parameters)\n";
  out += "Parameters (name, type, default, unit, range: description):\n";
  for (const auto& p : info->params)
    out += fmt::format("  {:<14} {:<16} {:<20} {:<8} {:<14} {}\n", p.name, type_name(p.type),
                       p.default_value ? format_value(*p.default_value) : p.optional ? "(optional)" : "(required)",
                       p.unit.empty() ? "-" : p.unit, p.allowed(), p.doc);
  return out;
}

namespace {
// A table cell: a '|' in the text (|v|, |a|) would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}
}  // namespace

std::string StyleRegistry::markdown_reference() const {
  std::string out;
  for (StyleKind kind : {StyleKind::fix, StyleKind::compute}) {
    out += fmt::format("\n## {} styles\n", kind == StyleKind::fix ? "Fix" : "Compute");
    for (const auto& s : styles_) {
      if (s.kind != kind) continue;
      out += fmt::format("\n### `{}`\n\n{}\n\n", s.name, s.summary);
      if (!s.values.empty()) out += fmt::format("Values: {}.\n\n", cell(s.values));
      if (s.params.empty()) {
        out += "No parameters.\n";
        continue;
      }
      out += "| parameter | type | default | unit | range | meaning |\n|---|---|---|---|---|---|\n";
      for (const auto& p : s.params)
        out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", p.name, type_name(p.type),
                           p.default_value ? fmt::format("`{}`", format_value(*p.default_value))
                           : std::string(p.optional ? "optional" : "required"),
                           p.unit.empty() ? "-" : p.unit, p.allowed(), cell(p.doc));
    }
  }
  return out;
}

}  // namespace pbf
