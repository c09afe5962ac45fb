#include "engine/io/vtk_appended.hpp"

#include <fmt/format.h>

#include <bit>

#include "engine/core/error.hpp"

namespace pbf {

// Array bytes are copied as they are and called LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtk_appended.cpp assumes a little-endian machine");

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

VtkAppendedFile::VtkAppendedFile(const std::string& path, const std::string& dataset)
    : path_(path),
      dataset_(dataset),
      head_(fmt::format("<?xml version=\"1.0\"?>\n"
                        "<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                        "  <{}>\n",
                        dataset, dataset)),
      file_(path) {}

void VtkAppendedFile::declare(const char* type, const std::string& name, int components, std::uint64_t bytes) {
  if (blocks_ > 0) throw Error(fmt::format("{}: array '{}' declared after the data began", path_, name));
  head_ += fmt::format(
      "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
      type, xml_escape(name), components, offset_);
  offset_ += sizeof(std::uint64_t) + bytes;
  sizes_.push_back(bytes);
}

void VtkAppendedFile::check_block_done() const {
  if (left_ != 0)
    throw Error(fmt::format("{}: block {} of {} is {} bytes short", path_, blocks_, sizes_.size(), left_));
}

void VtkAppendedFile::begin_block(std::uint64_t bytes) {
  check_block_done();
  if (blocks_ == 0) {  // the head is complete: write it, and open the appended block
    head_ += fmt::format("  </{}>\n  <AppendedData encoding=\"raw\">\n   _", dataset_);
    file_.write(head_);
  }
  if (blocks_ >= sizes_.size() || sizes_[blocks_] != bytes)
    throw Error(fmt::format("{}: block {} of {} bytes does not match the arrays declared", path_, blocks_ + 1, bytes));
  ++blocks_;
  left_ = bytes;
  file_.write(&bytes, sizeof bytes);
}

void VtkAppendedFile::write(const void* data, std::size_t bytes) {
  if (bytes > left_) throw Error(fmt::format("{}: block {} overflows its declared size", path_, blocks_));
  left_ -= bytes;
  file_.write(data, bytes);
}

void VtkAppendedFile::commit() {
  check_block_done();
  if (blocks_ != sizes_.size())
    throw Error(fmt::format("{}: {} arrays declared but {} written", path_, sizes_.size(), blocks_));
  if (blocks_ == 0) file_.write(head_ + fmt::format("  </{}>\n  <AppendedData encoding=\"raw\">\n   _", dataset_));
  file_.write("\n  </AppendedData>\n</VTKFile>\n");
  file_.commit();
}

}  // namespace pbf
