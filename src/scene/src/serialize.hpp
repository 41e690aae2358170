// Private: the cooked binary encoding of a Scene. One writer template serves both the cache file
// (VectorSink) and the content hash (HashSink), so the hash covers exactly what is stored.
// Encoding: little-endian PODs; vectors as u64 count + raw elements; strings as u64 length + bytes.
#pragma once

#include <fgb/scene/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <xxhash.h>

namespace fgb::scene::detail {

// Thrown by ByteReader on any inconsistency; the cache turns it into "corrupt entry, rebuild".
class CorruptData : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct VectorSink {
  std::vector<std::byte>& out;
  void write(const void* data, size_t size) {
    const auto* bytes = static_cast<const std::byte*>(data);
    out.insert(out.end(), bytes, bytes + size);
  }
};

class HashSink {
 public:
  HashSink() : state_(XXH3_createState()) { XXH3_64bits_reset(state_); }
  ~HashSink() { XXH3_freeState(state_); }
  HashSink(const HashSink&) = delete;
  HashSink& operator=(const HashSink&) = delete;
  void write(const void* data, size_t size) { XXH3_64bits_update(state_, data, size); }
  uint64_t digest() const { return XXH3_64bits_digest(state_); }

 private:
  XXH3_state_t* state_;
};

template <typename Sink>
class Writer {
 public:
  explicit Writer(Sink& sink) : sink_(sink) {}
  template <typename T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    sink_.write(&value, sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(static_cast<uint64_t>(values.size()));
    if (!values.empty()) sink_.write(values.data(), values.size() * sizeof(T));
  }
  void string(const std::string& text) {
    pod(static_cast<uint64_t>(text.size()));
    sink_.write(text.data(), text.size());
  }

 private:
  Sink& sink_;
};

class Reader {
 public:
  Reader(const std::byte* data, size_t size) : data_(data), size_(size) {}
  template <typename T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> array() {
    const auto count = pod<uint64_t>();
    if (count > (size_ - offset_) / sizeof(T)) throw CorruptData("array length past the end of the data");
    std::vector<T> values(count);
    if (count) std::memcpy(values.data(), take(count * sizeof(T)), count * sizeof(T));
    return values;
  }
  std::string string() {
    const auto length = pod<uint64_t>();
    if (length > size_ - offset_) throw CorruptData("string length past the end of the data");
    const std::byte* bytes = take(length);
    return std::string(reinterpret_cast<const char*>(bytes), length);
  }
  bool atEnd() const { return offset_ == size_; }

 private:
  const std::byte* take(size_t count) {
    if (count > size_ - offset_) throw CorruptData("unexpected end of data");
    const std::byte* at = data_ + offset_;
    offset_ += count;
    return at;
  }
  const std::byte* data_;
  size_t size_;
  size_t offset_ = 0;
};

template <typename Sink>
void writeScene(Writer<Sink>& w, const Scene& scene);
extern template void writeScene(Writer<VectorSink>&, const Scene&);
extern template void writeScene(Writer<HashSink>&, const Scene&);

// Reads what writeScene wrote and checks every cross reference (mesh ranges, indices, material and
// texture numbers), so a cooked scene handed to the renderer is always self-consistent.
Scene readScene(Reader& reader);

uint64_t hashScene(const Scene& scene);

}  // namespace fgb::scene::detail
