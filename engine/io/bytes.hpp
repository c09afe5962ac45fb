#pragma once
// Plain bytes in, plain bytes out: the restart format's building blocks. The writer appends
// values in this machine's byte order (the restart header records which); the reader checks
// every read against the bytes left, so a damaged file is an error, never a read past the
// end or an allocation sized by garbage.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"

namespace pbf {

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(&value, sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    append(s.data(), s.size());
  }
  template <class T>
  void put_array(const T* data, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(data, count * sizeof(T));
  }
  void append(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

class ByteReader {
 public:
  // `what` names the source in errors, e.g. "restart file 'out/run.400.restart'".
  ByteReader(const unsigned char* data, std::size_t size, std::string what)
      : data_(data), size_(size), what_(std::move(what)) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    copy_to(&value, sizeof(T));
    return value;
  }
  std::string get_string() {
    const std::uint64_t n = get<std::uint64_t>();
    require(n, 1);  // before the string allocates n bytes
    std::string s(n, '\0');
    copy_to(s.data(), n);
    return s;
  }
  // Reads `count` values into `out` (resized); the count is checked against the bytes left first.
  template <class T>
  void get_array(std::vector<T>& out, std::uint64_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(count, sizeof(T));
    out.resize(count);
    copy_to(out.data(), count * sizeof(T));
  }
  // `out` may be null when `count` is 0 (an empty field of a restart without particles).
  template <class T>
  void get_into(T* out, std::uint64_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(count, sizeof(T));
    copy_to(out, count * sizeof(T));
  }
  // A nested block of `size` bytes (a fix's saved state).
  ByteReader sub(std::uint64_t size, const std::string& what) {
    require(size, 1);
    const unsigned char* p = size > 0 ? data_ + pos_ : nullptr;
    pos_ += size;
    return ByteReader(p, size, what);
  }
  std::size_t left() const { return size_ - pos_; }
  const std::string& what() const { return what_; }

  // Throws unless `count` items of `item_size` bytes fit in what is left.
  void require(std::uint64_t count, std::size_t item_size) const {
    if (count > left() / item_size)
      throw Error(what_ + ": the data end early (the file is truncated or corrupted)");
  }

 private:
  // Copies the next n bytes to `out`. memcpy with a null pointer is undefined even for zero
  // bytes, and an empty vector's data() (an empty fix state, a field of no particles) and
  // an empty reader's data are null: so nothing is called for n = 0.
  void copy_to(void* out, std::size_t n) {
    require(n, 1);
    if (n == 0) return;
    std::memcpy(out, data_ + pos_, n);
    pos_ += n;
  }
  const unsigned char* data_;
  std::size_t size_, pos_ = 0;
  std::string what_;
};

}  // namespace pbf
