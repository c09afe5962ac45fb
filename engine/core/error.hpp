#pragma once
#include <stdexcept>
#include <string>
#include <utility>

namespace pbf {

// Every error the engine raises. `located` says the message already names where it
// happened (a scene file and line, a script line inside a callback); the command line
// then prints it as is instead of prefixing the line of the script that called in.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, bool located = false)
      : std::runtime_error(message), located_(located) {}
  bool located() const { return located_; }

 private:
  bool located_;
};

// A file that is not there, named by `path` as the user gave it. The command line adds,
// for a relative path, where the script that named it is, which the engine does not know.
class MissingFile : public Error {
 public:
  MissingFile(const std::string& message, std::string path) : Error(message), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace pbf
