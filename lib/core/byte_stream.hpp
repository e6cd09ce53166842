#pragma once
// Plain bytes in and out, for handing data between processes of one build (a distributed run's
// rank parts, sent by MPI): values and arrays of trivially copyable types (and of Vec3), written
// in order and read back in the same order. Not a file format: no versions, no byte-order
// conversion. Writer and reader share the names `value`, `vector` and `text`, so that one
// function template lists a structure's fields for both directions.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "core/types.hpp"

namespace corofem {

class ByteWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(&v, sizeof(T));
  }
  /// The element count, then the elements.
  template <class T>
  void vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    value<std::uint64_t>(values.size());
    append(values.data(), values.size() * sizeof(T));
  }
  void vector(const std::vector<Vec3>& points) {
    value<std::uint64_t>(points.size());
    for (const Vec3& p : points) append(p.data(), 3 * sizeof(double));
  }
  void text(const std::string& s) {
    value<std::uint64_t>(s.size());
    append(s.data(), s.size());
  }
  std::vector<char>& bytes() { return bytes_; }

 private:
  void append(const void* data, std::size_t count) {
    const char* begin = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), begin, begin + count);
  }
  std::vector<char> bytes_;
};

/// Reads what a ByteWriter wrote; throws NumericalFault, naming `what`, if the bytes end early.
class ByteReader {
 public:
  ByteReader(const std::vector<char>& bytes, std::string what)
      : bytes_(bytes), what_(std::move(what)) {}
  template <class T>
  void value(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof(T));
  }
  template <class T>
  void vector(std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    values.resize(count(sizeof(T)));
    take(values.data(), values.size() * sizeof(T));
  }
  void vector(std::vector<Vec3>& points) {
    points.resize(count(3 * sizeof(double)));
    for (Vec3& p : points) take(p.data(), 3 * sizeof(double));
  }
  void text(std::string& s) {
    s.resize(count(1));
    take(s.data(), s.size());
  }
  /// Whether every byte has been read.
  bool at_end() const { return offset_ == bytes_.size(); }

 private:
  /// An element count, checked against the bytes left.
  std::size_t count(std::size_t element_bytes) {
    std::uint64_t n = 0;
    value(n);
    if (n > (bytes_.size() - offset_) / element_bytes) fail();
    return static_cast<std::size_t>(n);
  }
  void take(void* data, std::size_t count) {
    if (count > bytes_.size() - offset_) fail();
    if (count > 0) std::memcpy(data, bytes_.data() + offset_, count);
    offset_ += count;
  }
  [[noreturn]] void fail() const {
    throw NumericalFault(what_ + ": the bytes received end early (" +
                         std::to_string(bytes_.size()) + " bytes)");
  }
  const std::vector<char>& bytes_;
  std::string what_;
  std::size_t offset_ = 0;
};

}  // namespace corofem
