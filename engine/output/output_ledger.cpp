#include "engine/output/output_ledger.hpp"

#include <fmt/format.h>

namespace pbf {

OutputLedger::Entry& OutputLedger::entry(const std::string& what) {
  for (Entry& e : entries_)
    if (e.what == what) return e;
  entries_.push_back(Entry{what, 0, 0, {}, {}});
  return entries_.back();
}

void OutputLedger::wrote(const std::string& what, const std::string& path) {
  Entry& e = entry(what);
  if (e.files > 0 && e.last == path) return;
  if (e.files == 0) e.first = path;
  e.last = path;
  ++e.files;
}

void OutputLedger::removed(const std::string& what) { ++entry(what).removed; }

std::string OutputLedger::summary() const {
  std::string text;
  for (const Entry& e : entries_) {
    if (e.files == 0) continue;
    text += fmt::format("  {}: ", e.what);
    if (e.files == 1) {
      text += e.first;
    } else {
      text += fmt::format("{} files, {} ... {}", e.files, e.first, e.last);
      if (e.removed > 0) text += fmt::format(" ({} older removed, {} kept)", e.removed, e.files - e.removed);
    }
    text += '\n';
  }
  return text;
}

}  // namespace pbf
