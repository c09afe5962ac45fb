#pragma once
// What the VTK XML files the engine writes (.vtu particle frames, .vtp solid surfaces) share:
// the one layout ParaView, VisIt and meshio all read fastest. LittleEndian, UInt64 block
// headers, every array "appended" into one raw block after the XML head, each a UInt64 byte
// count and the bytes. A writer declares its arrays (in the head, in its element structure),
// then writes one block per array in the same order; this class keeps the offsets and checks
// that the blocks match the declarations, so the two writers cannot drift apart.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/io/atomic_file.hpp"

namespace pbf {

// Text as an XML attribute value: &, < and " escaped.
std::string xml_escape(const std::string& s);

class VtkAppendedFile {
 public:
  // Starts the head of a file of `dataset` type ("UnstructuredGrid", "PolyData") at `path`,
  // written whole through AtomicFile: a reader never sees half a file.
  VtkAppendedFile(const std::string& path, const std::string& dataset);

  // The head: element tags as text (indented by the caller), and the arrays with their
  // sizes in bytes, in the order their blocks will follow.
  void head(const std::string& xml) { head_ += xml; }
  void declare(const char* type, const std::string& name, int components, std::uint64_t bytes);

  // The data: one block per declared array, in order. A block starts with its byte count and
  // may then be written in pieces (to stream an array rather than materialise it).
  void begin_block(std::uint64_t bytes);
  void write(const void* data, std::size_t bytes);
  void block(const void* data, std::uint64_t bytes) {
    begin_block(bytes);
    write(data, bytes);
  }

  // Closes the file and gives it its name; a pbf::Error if the blocks did not match the
  // declarations (a bug in the writer, caught before a reader is misled).
  void commit();

 private:
  void check_block_done() const;

  std::string path_, dataset_, head_;
  AtomicFile file_;
  std::vector<std::uint64_t> sizes_;  // declared bytes per array
  std::uint64_t offset_ = 0;          // the next array's offset into the appended block
  std::size_t blocks_ = 0;            // blocks begun
  std::uint64_t left_ = 0;            // bytes the current block still needs
};

}  // namespace pbf
