// Binary state for checkpoints: plain values and arrays of trivially copyable values, appended to
// a byte string, read back in the same order. A reader that runs past the end throws, so a
// truncated or foreign file is refused rather than half-restored.
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace grainlab {

class StateWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T, class A>
  void array(const std::vector<T, A>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value<uint64_t>(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value<uint64_t>(s.size());
    bytes_.append(s);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class StateReader {
 public:
  // (the bytes are held as a vector: over a std::string, GCC 12 warned of reads past a short
  // string's inline buffer wherever a reader was inlined, -Warray-bounds)
  explicit StateReader(const std::string& bytes) : bytes_(bytes.begin(), bytes.end()) {}
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  template <class T, class A>
  void array(std::vector<T, A>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = value<uint64_t>();
    if (n > (bytes_.size() - at_) / (sizeof(T) ? sizeof(T) : 1))
      throw std::runtime_error("checkpoint truncated");
    v.resize(n);
    std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  // A record count, refused when the bytes left cannot hold that many records of at least
  // `min_bytes_each` (a damaged count would otherwise allocate without bound).
  uint64_t count(size_t min_bytes_each) {
    const uint64_t n = value<uint64_t>();
    if (n > (bytes_.size() - at_) / (min_bytes_each ? min_bytes_each : 1))
      throw std::runtime_error("checkpoint truncated");
    return n;
  }
  std::string text() {
    const uint64_t n = value<uint64_t>();
    const char* p = take(n);
    return std::string(p, n);
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  const char* take(size_t n) {
    if (n > bytes_.size() - at_) throw std::runtime_error("checkpoint truncated");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::vector<char> bytes_;
  size_t at_ = 0;
};

}  // namespace grainlab
