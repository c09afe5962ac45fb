// The .vtu reader (the writer is in vtu.cpp).
#include "engine/io/vtu.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <iterator>
#include <memory>
#include <new>
#include <pugixml.hpp>
#include <set>
#include <string_view>

#include "engine/core/error.hpp"
#include "engine/core/particles.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

static_assert(std::endian::native == std::endian::little, "vtu_read.cpp assumes a little-endian machine");

namespace {

struct TypeInfo {
  const char* name;
  std::size_t size;
  void (*convert)(const char* bytes, std::size_t count, double* out);
};

template <class T>
void convert(const char* bytes, std::size_t count, double* out) {
  for (std::size_t i = 0; i < count; ++i) {
    T v;
    std::memcpy(&v, bytes + i * sizeof(T), sizeof(T));  // no alignment in the file
    out[i] = static_cast<double>(v);
  }
}

constexpr TypeInfo kTypes[] = {
    {"Int8", 1, convert<std::int8_t>},     {"UInt8", 1, convert<std::uint8_t>},
    {"Int16", 2, convert<std::int16_t>},   {"UInt16", 2, convert<std::uint16_t>},
    {"Int32", 4, convert<std::int32_t>},   {"UInt32", 4, convert<std::uint32_t>},
    {"Int64", 8, convert<std::int64_t>},   {"UInt64", 8, convert<std::uint64_t>},
    {"Float32", 4, convert<float>},        {"Float64", 8, convert<double>}};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

class VtuReader {
 public:
  explicit VtuReader(const std::string& path) : path_(path) {
    // fopen succeeds on a directory, which fails only at the first read; a device or a pipe
    // may never end (/dev/zero) or block the open (a FIFO): say what the path is instead.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::is_directory(status)) fail("cannot open the file: it is a directory");
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
      fail("cannot open the file: it is not a regular file (a device, a pipe or a socket)");
    file_.reset(std::fopen(path.c_str(), "rb"));
    if (!file_) fail(fmt::format("cannot open the file ({})", std::strerror(errno)));
    // The XML is held in memory, up to the appended data's first byte. Of a raw appended
    // array this process reads the size header and its share of the rows (Block); a base64
    // one is read whole, one array at a time, and only the share is kept.
    char buffer[65536];
    bool failed = false;
    try {
      for (std::size_t got; !head_complete() && (got = std::fread(buffer, 1, sizeof buffer, file_.get())) > 0;)
        bytes_.append(buffer, got);
      failed = std::ferror(file_.get());
    } catch (const std::bad_alloc&) {
      fail(fmt::format("cannot read the file: at {} bytes it does not fit in memory", bytes_.size()));
    }
    if (failed) fail(fmt::format("cannot read the file ({})", std::strerror(errno)));
    const auto size = std::filesystem::file_size(path, ec);
    file_size_ = ec ? bytes_.size() : static_cast<std::size_t>(size);
    if (bytes_.empty()) fail("empty file");
  }

  ParticleTable read() {
    parse_head();
    const auto root = doc_.child("VTKFile");
    if (!root) fail("not a VTK XML file: no <VTKFile> element");
    const std::string type = root.attribute("type").value();
    if (type != "UnstructuredGrid") fail(fmt::format("not an UnstructuredGrid (VTKFile type=\"{}\")", type));
    if (*root.attribute("compressor").value())
      fail(fmt::format("compressed files (compressor=\"{}\") are not supported; re-save it uncompressed "
                       "(ParaView: Save Data, Compressor Type: None)", root.attribute("compressor").value()));
    const std::string order = root.attribute("byte_order").as_string("LittleEndian");
    if (order != "LittleEndian") fail(fmt::format("byte_order \"{}\" is not supported, only LittleEndian", order));
    const std::string header = root.attribute("header_type").as_string("UInt32");
    if (header != "UInt32" && header != "UInt64")
      fail(fmt::format("header_type \"{}\" is not supported (UInt32 or UInt64)", header));
    header_size_ = header == "UInt64" ? 8 : 4;

    const auto grid = root.child("UnstructuredGrid");
    if (!grid) fail("no <UnstructuredGrid> element");
    const auto pieces = std::distance(grid.children("Piece").begin(), grid.children("Piece").end());
    if (pieces != 1) fail(fmt::format("{} <Piece> elements; only single-piece files are supported", pieces));
    const auto piece = grid.child("Piece");
    n_ = unsigned_attribute(piece, "NumberOfPoints");
    // Each point takes at least a byte per coordinate in any encoding; this bound also keeps
    // every size computed from n_ far from overflow.
    if (n_ > file_size_ / 3)
      fail_at(piece, fmt::format("NumberOfPoints = {} is more than a file of {} bytes can hold", n_, file_size_));

    ParticleTable table;
    table.path = path_;
    share_ = Particles::share_of(n_, comm::distributed());
    table.count = share_.end - share_.first;
    table.first_row = share_.first;
    table.total = n_;
    const auto points = piece.child("Points").child("DataArray");
    if (!points) fail_at(piece, "no <Points> with a <DataArray>: the file has no particle positions");
    table.columns.push_back(read_array(points, "position", "the Points array", 3));
    std::set<std::string> names{"position"};  // a set: many arrays cost no quadratic search
    for (const auto& a : piece.child("PointData").children("DataArray")) {
      const std::string name = a.attribute("Name").value();
      if (name.empty()) fail_at(a, "a PointData DataArray has no Name");
      if (!names.insert(name).second)
        fail_at(a, fmt::format("PointData array '{}' appears twice (or clashes with the Points, read as 'position')",
                               name));
      table.columns.push_back(read_array(a, name, fmt::format("PointData array '{}'", name)));
    }
    return table;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(fmt::format("{}: {}", path_, message), true);
  }
  // The 1-based line of a byte offset; 0 if it lies outside the file.
  long line_of(std::ptrdiff_t offset) const {
    if (offset < 0 || static_cast<std::size_t>(offset) > bytes_.size()) return 0;
    return 1 + std::count(bytes_.begin(), bytes_.begin() + offset, '\n');
  }
  [[noreturn]] void fail_at(std::ptrdiff_t offset, const std::string& message) const {
    if (line_of(offset) == 0) fail(message);
    throw Error(fmt::format("{}:{}: {}", path_, line_of(offset), message), true);
  }
  [[noreturn]] void fail_at(pugi::xml_node node, const std::string& message) const {
    fail_at(node.offset_debug(), message);
  }

  // Whether bytes_ reaches past <AppendedData ...> to the first byte that is not a space
  // (the '_' that starts the data), so that the head is complete and the rest can wait.
  bool head_complete() {
    static constexpr std::string_view kTag = "<AppendedData";
    if (tag_ == std::string::npos) {  // searched from where the last search left off
      tag_ = bytes_.find(kTag, scanned_);
      scanned_ = bytes_.size() > kTag.size() ? bytes_.size() - kTag.size() : 0;
      if (tag_ == std::string::npos) return false;
    }
    const auto gt = bytes_.find('>', tag_);
    if (gt == std::string::npos) return false;
    std::size_t p = gt + 1;
    while (p < bytes_.size() && is_space(bytes_[p])) ++p;
    return p < bytes_.size();
  }

  // Bytes [from, from + n) of the file (n clamped to its end).
  std::string read_at(std::size_t from, std::size_t n) const {
    std::string out;
    if (from >= file_size_) return out;
    n = std::min(n, file_size_ - from);
    try {
      out.resize(n);
    } catch (const std::bad_alloc&) {
      fail(fmt::format("cannot read the file: a block of {} bytes does not fit in memory", n));
    }
    if (std::fseek(file_.get(), static_cast<long>(from), SEEK_SET) != 0 ||
        std::fread(out.data(), 1, n, file_.get()) != n)
      fail(fmt::format("cannot read the file ({})", std::ferror(file_.get()) ? std::strerror(errno) : "it is shorter than it was"));
    return out;
  }

  // pugixml cannot take raw binary, so only the XML before <AppendedData> is parsed (with
  // the AppendedData tag made empty and VTKFile closed); the block itself is located here.
  void parse_head() {
    const auto tag = bytes_.find("<AppendedData");
    std::string head;  // stays empty when the whole file is XML
    if (tag != std::string::npos) {
      const auto gt = bytes_.find('>', tag);
      if (gt == std::string::npos) fail("truncated file: it ends inside the <AppendedData> tag");
      const bool empty = bytes_[gt - 1] == '/';
      head = bytes_.substr(0, empty ? gt + 1 : gt) + (empty ? "" : "/>") + "</VTKFile>";
      if (!empty) locate_block(gt + 1);
    }
    const std::string& xml = tag == std::string::npos ? bytes_ : head;
    const auto result = doc_.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result && result.status != pugi::status_no_document_element && tag == std::string::npos) {
      // Every VTK XML file ends with </VTKFile>: without it the error is a symptom of a cut.
      if (!trim(bytes_).ends_with("</VTKFile>"))
        fail(fmt::format("truncated file: it does not end with </VTKFile> (XML error at line {}: {})",
                         line_of(result.offset), result.description()));
    }
    if (!result) fail_at(result.offset, fmt::format("not valid XML: {}", result.description()));
    const auto appended = doc_.child("VTKFile").child("AppendedData");
    const std::string encoding = appended.attribute("encoding").as_string("raw");
    if (appended && encoding != "raw" && encoding != "base64")
      fail_at(appended, fmt::format("AppendedData encoding \"{}\" is not supported (raw or base64)", encoding));
    base64_block_ = encoding == "base64";
    if (block_begin_ != 0) collect_offsets();
  }

  // The offsets of every appended DataArray (those of <Cells> too, which are not read):
  // an array's block runs from its offset to the next one, so each block can be checked to
  // hold exactly the header and the bytes its array needs. That is how a header_type that
  // disagrees with the data is caught, rather than read as shifted, wrong numbers.
  void collect_offsets() {
    struct Walker : pugi::xml_tree_walker {  // pugixml walks iteratively: deep XML is no danger
      VtuReader* reader;
      bool for_each(pugi::xml_node& node) override {
        const std::string_view name = node.name(), format = node.attribute("format").value();
        if (name != "DataArray" || format != "appended") return true;
        const auto offset = reader->unsigned_attribute(node, "offset");
        if (!reader->offsets_.insert(offset).second)
          reader->fail_at(node, fmt::format("two DataArrays start at offset {} of the appended data", offset));
        return true;
      }
    } walker;
    walker.reader = this;
    doc_.traverse(walker);
  }

  // A binary block: an array's size header and data, in memory (decoded base64) or where it
  // lies in the file (a raw appended array), whose bytes are then read only where asked.
  struct Block {
    std::string_view memory;
    const VtuReader* file = nullptr;  // set: the block is the file's bytes [at, at + size)
    std::size_t at = 0, size = 0;
    std::string bytes(std::size_t from, std::size_t n) const {
      if (from >= size) return {};
      n = std::min(n, size - from);
      return file ? file->read_at(at + from, n) : std::string(memory.substr(from, n));
    }
  };
  static Block in_memory(std::string_view bytes) { return Block{bytes, nullptr, 0, bytes.size()}; }

  // The appended block at `offset`, up to the next block's offset; `last`: no block follows.
  Block appended_block(std::uint64_t offset, bool& last) const {
    const std::size_t size = block_end_ - block_begin_;
    const auto next = offsets_.upper_bound(offset);
    last = next == offsets_.end() || *next >= size;
    const std::size_t end = last ? size : *next;
    return Block{{}, this, block_begin_ + offset, end - offset};
  }

  void locate_block(std::size_t p) {
    while (p < bytes_.size() && is_space(bytes_[p])) ++p;
    if (p == bytes_.size()) fail("truncated file: it ends before the appended data");
    if (bytes_[p] != '_') fail_at(p, "the appended data does not start with '_'");
    block_begin_ = p + 1;
    // The last closing tag: the binary data before it may contain anything. It is looked for
    // in the file's last megabyte (only spaces and </VTKFile> may follow it).
    const std::size_t window = std::min<std::size_t>(file_size_ - block_begin_, std::size_t{1} << 20);
    const std::string tail = read_at(file_size_ - window, window);
    const auto found = tail.rfind("</AppendedData>");
    if (found == std::string::npos) fail("truncated file: no closing </AppendedData>");
    const std::size_t close = file_size_ - window + found;
    block_end_ = close;
    if (trim(std::string_view(tail).substr(found + std::strlen("</AppendedData>"))) != "</VTKFile>")
      fail("truncated file: </AppendedData> is not followed by </VTKFile>");
  }

  std::uint64_t unsigned_attribute(pugi::xml_node node, const char* name) const {
    const std::string_view text = node.attribute(name).value();
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size())
      fail_at(node, fmt::format("<{}> needs {} = a non-negative integer, got \"{}\"", node.name(), name, text));
    return v;
  }

  // One DataArray as a column; `components` > 0: the number it must have.
  Column read_array(pugi::xml_node a, const std::string& column, const std::string& what, int components = 0) {
    Column c{column, 1, {}};
    if (a.attribute("NumberOfComponents")) {
      const auto k = unsigned_attribute(a, "NumberOfComponents");
      if (k < 1 || k > 1024) fail_at(a, fmt::format("{} has NumberOfComponents = {}", what, k));
      c.components = static_cast<int>(k);
    }
    if (components > 0 && c.components != components)
      fail_at(a, fmt::format("{} has {} components, expected {}", what, c.components, components));
    const std::string type_text = a.attribute("type").value();
    const auto type = std::find_if(std::begin(kTypes), std::end(kTypes),
                                   [&](const TypeInfo& t) { return type_text == t.name; });
    if (type == std::end(kTypes)) fail_at(a, fmt::format("{} has unknown type \"{}\"", what, type_text));
    const std::size_t count = n_ * c.components;  // < 2^62: n_ is bounded by the file size
    const std::size_t bytes = count * type->size;
    const std::string format = a.attribute("format").value();
    if (format == "ascii") {
      c.values = ascii(a, a.child_value(), count, what);
      const auto k = static_cast<std::size_t>(c.components);  // this process's share of the rows
      c.values.erase(c.values.begin() + static_cast<std::ptrdiff_t>(share_.end * k), c.values.end());
      c.values.erase(c.values.begin(), c.values.begin() + static_cast<std::ptrdiff_t>(share_.first * k));
      return c;
    }
    Block block;
    std::string decoded;  // base64 data, decoded
    auto from_base64 = [&](std::string_view text) {
      decoded = base64(a, text, what);
      return in_memory(decoded);
    };
    bool last = true;  // no array's data follow the block
    if (format == "binary") {  // inline base64
      block = from_base64(a.child_value());
    } else if (format == "appended") {
      if (block_begin_ == 0)
        fail_at(a, fmt::format("{} is format=\"appended\" but the file has no appended data", what));
      const auto offset = unsigned_attribute(a, "offset");
      const std::size_t size = block_end_ - block_begin_;
      if (offset >= size)
        fail_at(a, fmt::format("{}: offset {} is beyond the appended data ({} bytes)", what, offset, size));
      block = appended_block(offset, last);
      if (base64_block_) block = from_base64(block.bytes(0, block.size));
    } else {
      fail_at(a, fmt::format("{} has format \"{}\" (expected appended, binary or ascii)", what, format));
    }
    // Raw appended data end in the whitespace before </AppendedData>; base64 skips whitespace.
    check_payload(a, block, bytes, what, last && format == "appended" && !base64_block_, !last);
    // This process's share of the rows, after the size header.
    const auto k = static_cast<std::size_t>(c.components);
    const std::string share = block.bytes(header_size_ + share_.first * k * type->size,
                                          (share_.end - share_.first) * k * type->size);
    c.values.resize((share_.end - share_.first) * k);
    type->convert(share.data(), c.values.size(), c.values.data());
    return c;
  }

  // The size a block's header of `header` bytes announces (the block holds that many).
  static std::uint64_t announced(const Block& block, std::size_t header) {
    std::uint64_t size = 0;
    std::memcpy(&size, block.bytes(0, header).data(), header);  // little-endian: the low bytes first
    return size;
  }

  // Whether `block` is a size header of `header` bytes announcing `expected` bytes, then
  // those bytes, then nothing but (if `trailing_space`) whitespace.
  static bool block_fits(const Block& block, std::size_t header, std::size_t expected, bool trailing_space) {
    if (block.size < header) return false;
    const std::uint64_t size = announced(block, header);
    if (size != expected || block.size - header < size) return false;
    const std::size_t rest = block.size - header - size;
    return rest == 0 || (trailing_space && trim(block.bytes(header + size, rest)).empty());
  }

  // Checks one binary block: a byte count (of header_type), then that many bytes, which
  // must be the `expected` bytes the array needs, and nothing more. Each mismatch gets its
  // own message; one explained by the other header size names the header_type.
  // `followed`: the block ends where another array's starts (appended data).
  void check_payload(pugi::xml_node a, const Block& block, std::size_t expected, const std::string& what,
                     bool trailing_space, bool followed) const {
    if (block_fits(block, header_size_, expected, trailing_space)) return;
    const std::size_t other = header_size_ == 4 ? 8 : 4;
    if (block_fits(block, other, expected, trailing_space))
      fail_at(a, fmt::format("{}: header_type=\"{}\" says block sizes are {}-byte numbers, but the data have "
                             "{}-byte ones: the header_type does not match the data (it should be \"{}\")",
                             what, header_name(header_size_), header_size_, other, header_name(other)));
    if (block.size < header_size_) fail_at(a, fmt::format("truncated file: {} ends inside its size header", what));
    const std::uint64_t size = announced(block, header_size_);
    if (size != expected)
      fail_at(a, fmt::format("{} holds {} bytes, but NumberOfPoints = {} needs {}", what, size, n_, expected));
    if (block.size - header_size_ < size && followed)
      fail_at(a, fmt::format("{} needs {} bytes, but the next array's data start after {} (their offsets overlap)",
                             what, size, block.size - header_size_));
    if (block.size - header_size_ < size)
      fail_at(a, fmt::format("truncated file: {} needs {} bytes, only {} are there", what, size,
                             block.size - header_size_));
    fail_at(a, fmt::format("{}: its block holds {} bytes after the {} its size header announces (blocks overlap, or "
                           "the header_type does not match the data)",
                           what, block.size - header_size_ - size, size));
  }

  static const char* header_name(std::size_t size) { return size == 4 ? "UInt32" : "UInt64"; }

  // Decodes base64 four characters at a time, allowing '=' padding at the end of any
  // quantum: VTK encodes the size header and the data as two base64 runs, other writers as
  // one; both decode to the same bytes this way. Whitespace is skipped.
  std::string base64(pugi::xml_node a, std::string_view text, const std::string& what) const {
    static constexpr std::string_view alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve(text.size() / 4 * 3);
    int q[4], k = 0;
    for (const char ch : text) {
      if (is_space(ch)) continue;
      const auto pos = alphabet.find(ch);
      if (pos == std::string_view::npos && ch != '=')
        fail_at(a, fmt::format("{}: '{}' is not a base64 character", what, printable(ch)));
      q[k++] = pos == std::string_view::npos ? -1 : static_cast<int>(pos);
      if (k < 4) continue;
      k = 0;
      if (q[0] < 0 || q[1] < 0 || (q[2] < 0 && q[3] >= 0)) fail_at(a, fmt::format("{}: misplaced base64 '='", what));
      out += static_cast<char>(q[0] << 2 | q[1] >> 4);
      if (q[2] >= 0) out += static_cast<char>((q[1] & 15) << 4 | q[2] >> 2);
      if (q[3] >= 0) out += static_cast<char>((q[2] & 3) << 6 | q[3]);
    }
    if (k != 0)
      fail_at(a, fmt::format("truncated file: {} ends inside a group of four base64 characters", what));
    return out;
  }

  // A character for a message: itself if printable ASCII, else its code.
  static std::string printable(char ch) {
    const auto u = static_cast<unsigned char>(ch);
    return u >= 0x20 && u < 0x7f ? std::string(1, ch) : fmt::format("\\x{:02x}", u);
  }

  std::vector<double> ascii(pugi::xml_node a, const char* text, std::size_t count, const std::string& what) const {
    const std::string_view s(text);
    if (count > (s.size() + 1) / 2)  // each value needs a character and a separator
      fail_at(a, fmt::format("{} holds too few values for NumberOfPoints = {}", what, n_));
    std::vector<double> values;
    values.reserve(count);
    std::size_t p = 0;
    while (true) {
      while (p < s.size() && is_space(s[p])) ++p;
      if (p == s.size()) break;
      std::size_t e = p;
      while (e < s.size() && !is_space(s[e])) ++e;
      const auto token = s.substr(p, e - p);
      if (values.size() == count)
        fail_at(a, fmt::format("{} holds more than the {} values NumberOfPoints = {} needs", what, count, n_));
      double v = 0;
      // from_chars refuses a leading '+'; skip one, but only before a digit or a point ("+-1").
      const bool plus = token.size() > 1 && token[0] == '+' && token[1] != '-';
      const auto [end, ec] = std::from_chars(token.data() + plus, token.data() + token.size(), v);
      if (ec == std::errc::result_out_of_range)
        fail_at(a, fmt::format("{}: '{}' is out of the range of a double", what, token.substr(0, 40)));
      if (ec != std::errc() || end != token.data() + token.size())
        fail_at(a, fmt::format("{}: '{}' is not a number", what, token.substr(0, 40)));
      values.push_back(v);
      p = e;
    }
    if (values.size() != count)
      fail_at(a, fmt::format("{} holds {} values, but NumberOfPoints = {} needs {}", what, values.size(), n_, count));
    return values;
  }

  std::string path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_{nullptr, std::fclose};
  std::string bytes_;  // the file up to the appended data's first byte (the whole file if it has none)
  std::size_t file_size_ = 0;
  std::size_t tag_ = std::string::npos, scanned_ = 0;  // head_complete()'s search
  Particles::Share share_;  // this process's rows
  pugi::xml_document doc_;
  std::size_t block_begin_ = 0, block_end_ = 0;  // the appended data, after '_'; 0: none
  std::set<std::uint64_t> offsets_;               // where its blocks start
  bool base64_block_ = false;
  std::size_t header_size_ = 4;
  std::uint64_t n_ = 0;
};

}  // namespace

ParticleTable read_vtu(const std::string& path) { return VtuReader(path).read(); }

}  // namespace pbf
