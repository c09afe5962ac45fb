#pragma once
#include <stdexcept>
#include <string>

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

}  // namespace pbf
