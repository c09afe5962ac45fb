#pragma once
// The live view's page, its style and scripts, and three.js (Debian's libjs-three), built
// into the binary (view_assets.cpp.in): a run serves them without finding files, and no
// request can name any other file.
#include <cstddef>
#include <span>

namespace pbf {

struct ViewAsset {
  const char* path;  // as requested, "/view.js"
  const char* type;  // Content-Type
  const unsigned char* data;
  std::size_t size;
};

std::span<const ViewAsset> view_assets();

}  // namespace pbf
