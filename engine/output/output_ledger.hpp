#pragma once
// What a script's runs wrote, for the list the command line prints at the end: each output
// (a dump's frames, a CSV, the restarts) with how many files and the first and last of them.
#include <cstdint>
#include <string>
#include <vector>

namespace pbf {

class OutputLedger {
 public:
  struct Entry {
    std::string what;        // "text frames (fix 'frames')", "restarts", "thermo CSV"
    std::int64_t files = 0;  // written (a file written again counts once in a row)
    std::int64_t removed = 0;
    std::string first, last;
  };

  // A file of the output `what` was written (or written again: a CSV that grows, a
  // collection rewritten with each frame).
  void wrote(const std::string& what, const std::string& path);
  // A file of `what` was deleted (an older restart, beyond those the fix keeps).
  void removed(const std::string& what);
  const std::vector<Entry>& entries() const { return entries_; }
  // One line an output: "  text frames (fix 'frames'): 16 files, out/frame_00000.txt ...
  // out/frame_00015.txt"; "" when nothing was written.
  std::string summary() const;

 private:
  Entry& entry(const std::string& what);
  std::vector<Entry> entries_;  // in the order of their first file
};

}  // namespace pbf
