// The fast EXR reader (see exr_fast_reader.hpp).
#include "exr_fast_reader.hpp"

#include <fgb/harness/base/parallel.hpp>

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <vector>

#if defined(__linux__)
#include <dlfcn.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define FGB_EXR_F16C 1
#else
#define FGB_EXR_F16C 0
#endif

namespace fgb::harness::detail {
namespace {
struct Libdeflate {
  using Alloc = void* (*)();
  using ZlibDecompress = int (*)(void*, const void*, std::size_t, void*, std::size_t, std::size_t*);
  using Free = void (*)(void*);
  Alloc alloc = nullptr;
  ZlibDecompress zlibDecompress = nullptr;
  Free release = nullptr;
};

// Null when libdeflate is not installed.
const Libdeflate* libdeflate() {
  static const std::optional<Libdeflate> library = []() -> std::optional<Libdeflate> {
#if defined(__linux__)
    void* handle = dlopen("libdeflate.so.0", RTLD_NOW | RTLD_LOCAL);
    if (!handle) return std::nullopt;
    auto symbol = [handle]<typename F>(const char* name, F& out) {
      void* address = dlsym(handle, name);
      static_assert(sizeof address == sizeof out);
      std::memcpy(&out, &address, sizeof out);
      return address != nullptr;
    };
    Libdeflate l;
    if (symbol("libdeflate_alloc_decompressor", l.alloc) && symbol("libdeflate_zlib_decompress", l.zlibDecompress) &&
        symbol("libdeflate_free_decompressor", l.release)) {
      return l;
    }
#endif
    return std::nullopt;
  }();
  return library ? &*library : nullptr;
}

// Bounds-checked little-endian reads from a byte buffer; any overrun makes ok() false.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, std::size_t size, std::size_t position = 0) : data_(data), size_(size), position_(position) {}
  template <typename T>
  T read() {
    T value{};
    if (position_ > size_ || size_ - position_ < sizeof(T)) {
      ok_ = false;
      return value;
    }
    std::memcpy(&value, data_ + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }
  std::string readString() {  // null-terminated
    const std::size_t start = position_;
    while (position_ < size_ && data_[position_] != 0) ++position_;
    if (position_ >= size_) {
      ok_ = false;
      return {};
    }
    return std::string(reinterpret_cast<const char*>(data_ + start), position_++ - start);
  }
  void skip(std::size_t n) {
    if (position_ > size_ || size_ - position_ < n) ok_ = false;
    position_ = ok_ ? position_ + n : size_;
  }
  std::size_t position() const { return position_; }
  bool ok() const { return ok_; }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t position_;
  bool ok_ = true;
};

struct ExrLayout {
  enum Compression : uint8_t { None = 0, Zips = 2, Zip = 3 };
  Compression compression = None;
  int32_t minX = 0, minY = 0, maxX = -1, maxY = -1;
  int linesPerChunk = 1;
  std::size_t bytesPerLine = 0;
  // Per output channel (R, G, B, A): pixel type (0 uint, 1 half, 2 float) and byte offset of its
  // values within a line; type -1 where the file lacks the channel.
  std::array<int, 4> type{-1, -1, -1, -1};
  std::array<std::size_t, 4> offset{};
  std::vector<uint64_t> chunkOffsets;
  long width() const { return static_cast<long>(maxX) - minX + 1; }
  long height() const { return static_cast<long>(maxY) - minY + 1; }
};

std::optional<ExrLayout> parseSimpleExr(const std::vector<uint8_t>& file) {
  if constexpr (std::endian::native != std::endian::little) return std::nullopt;
  ByteReader in(file.data(), file.size());
  if (in.read<uint32_t>() != 20000630u) return std::nullopt;
  const auto version = in.read<uint32_t>();
  constexpr uint32_t kLongNames = 0x400;
  if ((version & 0xffu) != 2 || (version & ~(0xffu | kLongNames)) != 0) return std::nullopt;  // tiled, deep, multi-part
  ExrLayout layout;
  bool haveChannels = false, haveCompression = false, haveWindow = false;
  struct Channel {
    std::string name;
    int32_t type;
  };
  std::vector<Channel> channels;
  for (;;) {
    const std::string name = in.readString();
    if (!in.ok()) return std::nullopt;
    if (name.empty()) break;  // end of header
    const std::string type = in.readString();
    const auto size = in.read<int32_t>();
    if (!in.ok() || size < 0) return std::nullopt;
    const std::size_t end = in.position() + static_cast<std::size_t>(size);
    if (name == "channels" && type == "chlist") {
      for (;;) {
        const std::string channel = in.readString();
        if (!in.ok()) return std::nullopt;
        if (channel.empty()) break;
        const auto pixelType = in.read<int32_t>();
        in.skip(4);  // pLinear, reserved
        const auto xSampling = in.read<int32_t>(), ySampling = in.read<int32_t>();
        if (!in.ok() || pixelType < 0 || pixelType > 2 || xSampling != 1 || ySampling != 1) return std::nullopt;
        channels.push_back({channel, pixelType});
      }
      haveChannels = true;
    } else if (name == "compression" && type == "compression" && size == 1) {
      const auto c = in.read<uint8_t>();
      if (c != ExrLayout::None && c != ExrLayout::Zips && c != ExrLayout::Zip) return std::nullopt;
      layout.compression = static_cast<ExrLayout::Compression>(c);
      haveCompression = true;
    } else if (name == "dataWindow" && type == "box2i" && size == 16) {
      layout.minX = in.read<int32_t>();
      layout.minY = in.read<int32_t>();
      layout.maxX = in.read<int32_t>();
      layout.maxY = in.read<int32_t>();
      haveWindow = true;
    }
    if (!in.ok() || in.position() > end) return std::nullopt;
    in.skip(end - in.position());
  }
  if (!haveChannels || !haveCompression || !haveWindow || layout.width() <= 0 || layout.height() <= 0 ||
      layout.width() > (1 << 24) || layout.height() > (1 << 24)) {
    return std::nullopt;
  }
  std::sort(channels.begin(), channels.end(), [](const Channel& a, const Channel& b) { return a.name < b.name; });
  const auto width = static_cast<std::size_t>(layout.width());
  for (const Channel& channel : channels) {
    static constexpr std::array<const char*, 4> kNames{"R", "G", "B", "A"};
    for (std::size_t c = 0; c < kNames.size(); ++c) {
      if (channel.name == kNames[c]) {
        layout.type[c] = channel.type;
        layout.offset[c] = layout.bytesPerLine;
      }
    }
    layout.bytesPerLine += width * (channel.type == 1 ? 2u : 4u);
  }
  if (layout.type[0] < 0 && layout.type[1] < 0 && layout.type[2] < 0) return std::nullopt;  // no colour: OpenEXR's RGBA interface
  layout.linesPerChunk = layout.compression == ExrLayout::Zip ? 16 : 1;
  const auto chunks = static_cast<std::size_t>((layout.height() + layout.linesPerChunk - 1) / layout.linesPerChunk);
  layout.chunkOffsets.resize(chunks);
  for (uint64_t& offset : layout.chunkOffsets) offset = in.read<uint64_t>();
  if (!in.ok()) return std::nullopt;
  return layout;
}

// Half floats to float, four channels interleaved into RGBA (missing ones: colour 0, alpha 1).
void convertLineScalar(const std::array<const uint8_t*, 4>& source, const std::array<int, 4>& type, std::size_t width, float* out) {
  for (std::size_t x = 0; x < width; ++x) {
    for (std::size_t c = 0; c < 4; ++c) {
      float v = c == 3 ? 1.0f : 0.0f;
      if (type[c] == 1) {
        uint16_t bits;
        std::memcpy(&bits, source[c] + 2 * x, sizeof bits);
        Imath::half h;
        h.setBits(bits);
        v = static_cast<float>(h);
      } else if (type[c] == 2) {
        std::memcpy(&v, source[c] + 4 * x, sizeof v);
      } else if (type[c] == 0) {
        uint32_t u;
        std::memcpy(&u, source[c] + 4 * x, sizeof u);
        v = static_cast<float>(u);
      }
      out[4 * x + c] = v;
    }
  }
}

#if FGB_EXR_F16C
// Colour and alpha as half floats or missing: eight pixels at a time with F16C, transposed into RGBA.
__attribute__((target("avx2,f16c"))) void convertHalfLineAvx2(const std::array<const uint8_t*, 4>& source, const std::array<int, 4>& type,
                                                               std::size_t width, float* out) {
  std::size_t x = 0;
  for (; x + 8 <= width; x += 8) {
    __m256 v[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_set1_ps(1.0f)};
    for (std::size_t c = 0; c < 4; ++c) {
      if (type[c] == 1) v[c] = _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(source[c] + 2 * x)));
    }
    const __m256 rg0 = _mm256_unpacklo_ps(v[0], v[1]), rg1 = _mm256_unpackhi_ps(v[0], v[1]);
    const __m256 ba0 = _mm256_unpacklo_ps(v[2], v[3]), ba1 = _mm256_unpackhi_ps(v[2], v[3]);
    const __m256 p0 = _mm256_shuffle_ps(rg0, ba0, 0x44), p1 = _mm256_shuffle_ps(rg0, ba0, 0xee);
    const __m256 p2 = _mm256_shuffle_ps(rg1, ba1, 0x44), p3 = _mm256_shuffle_ps(rg1, ba1, 0xee);
    float* o = out + 4 * x;
    _mm256_storeu_ps(o + 0, _mm256_permute2f128_ps(p0, p1, 0x20));
    _mm256_storeu_ps(o + 8, _mm256_permute2f128_ps(p2, p3, 0x20));
    _mm256_storeu_ps(o + 16, _mm256_permute2f128_ps(p0, p1, 0x31));
    _mm256_storeu_ps(o + 24, _mm256_permute2f128_ps(p2, p3, 0x31));
  }
  if (x < width) {
    std::array<const uint8_t*, 4> rest{};
    for (std::size_t c = 0; c < 4; ++c) rest[c] = type[c] == 1 ? source[c] + 2 * x : nullptr;
    convertLineScalar(rest, type, width - x, out + 4 * x);
  }
}

#endif

// AVX2 and F16C available, and not capped by FGBENCH_FLIP_ISA=baseline (for tests).
bool useAvx2() {
#if FGB_EXR_F16C
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("f16c");
  }();
  const char* cap = std::getenv("FGBENCH_FLIP_ISA");
  return has && !(cap && std::string_view(cap) == "baseline");
#else
  return false;
#endif
}

// OpenEXR's ZIP filter, undone: the bytes are deltas (+128) of a running sum, and the first and
// second halves of the result go to the even and odd bytes of the output.
void undoZipPredictorScalar(uint8_t* delta, uint8_t* out, std::size_t size) {
  uint8_t value = 128;  // so that the first byte comes out as it is
  for (std::size_t i = 0; i < size; ++i) {
    value = static_cast<uint8_t>(value + delta[i] - 128);
    delta[i] = value;
  }
  const std::size_t half = (size + 1) / 2;
  for (std::size_t i = 0; i < size; ++i) out[i] = delta[(i & 1) ? half + i / 2 : i / 2];
}

#if FGB_EXR_F16C
// The same, 16 bytes at a time: a prefix sum by doubling shifts, then byte interleaving.
__attribute__((target("avx2"))) void undoZipPredictorAvx2(uint8_t* delta, uint8_t* out, std::size_t size) {
  const __m128i bias = _mm_set1_epi8(static_cast<char>(0x80)), last = _mm_set1_epi8(15);
  __m128i running = _mm_set1_epi8(static_cast<char>(0x80));
  std::size_t i = 0;
  for (; i + 16 <= size; i += 16) {
    __m128i x = _mm_xor_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(delta + i)), bias);  // delta - 128
    x = _mm_add_epi8(x, _mm_slli_si128(x, 1));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 2));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 4));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 8));
    x = _mm_add_epi8(x, running);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(delta + i), x);
    running = _mm_shuffle_epi8(x, last);
  }
  auto value = static_cast<uint8_t>(_mm_cvtsi128_si32(running));
  for (; i < size; ++i) {
    value = static_cast<uint8_t>(value + delta[i] - 128);
    delta[i] = value;
  }
  const std::size_t half = (size + 1) / 2;
  const uint8_t* even = delta;
  const uint8_t* odd = delta + half;
  const std::size_t pairs = size / 2;  // complete (even, odd) pairs
  std::size_t k = 0;
  for (; k + 16 <= pairs; k += 16) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(even + k));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(odd + k));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * k), _mm_unpacklo_epi8(a, b));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * k + 16), _mm_unpackhi_epi8(a, b));
  }
  for (; k < pairs; ++k) {
    out[2 * k] = even[k];
    out[2 * k + 1] = odd[k];
  }
  if (size % 2) out[size - 1] = even[pairs];
}
#endif

void undoZipPredictor(uint8_t* delta, uint8_t* out, std::size_t size, [[maybe_unused]] bool avx2) {
#if FGB_EXR_F16C
  if (avx2) {
    undoZipPredictorAvx2(delta, out, size);
    return;
  }
#endif
  undoZipPredictorScalar(delta, out, size);
}

// Decodes chunk `index` into the image; false for anything unexpected (then OpenEXR reads the file).
bool decodeChunk(const std::vector<uint8_t>& file, const ExrLayout& layout, std::size_t index, void* decompressor, bool avx2,
                 std::vector<uint8_t>& inflated, std::vector<uint8_t>& lines, Image& image) {
  ByteReader in(file.data(), file.size(), static_cast<std::size_t>(layout.chunkOffsets[index]));
  const auto y = in.read<int32_t>();
  const auto packedSize = in.read<int32_t>();
  if (!in.ok() || packedSize < 0 || file.size() - in.position() < static_cast<std::size_t>(packedSize)) return false;
  // Chunk i holds lines minY + i * linesPerChunk on (the offset table is in y order whatever the
  // line order): so every line comes from exactly one chunk.
  if (static_cast<long>(y) != layout.minY + static_cast<long>(index) * layout.linesPerChunk) return false;
  const auto lineCount = static_cast<std::size_t>(std::min<long>(layout.linesPerChunk, static_cast<long>(layout.maxY) - y + 1));
  const std::size_t rawSize = lineCount * layout.bytesPerLine;
  const uint8_t* packed = file.data() + in.position();
  const uint8_t* raw = packed;
  if (static_cast<std::size_t>(packedSize) != rawSize) {
    if (layout.compression == ExrLayout::None || static_cast<std::size_t>(packedSize) > rawSize) return false;
    // zlib stream of the byte-delta-coded, even/odd-split data.
    inflated.resize(rawSize);
    lines.resize(rawSize);
    std::size_t actual = 0;
    if (libdeflate()->zlibDecompress(decompressor, packed, static_cast<std::size_t>(packedSize), inflated.data(), rawSize, &actual) != 0 ||
        actual != rawSize) {
      return false;
    }
    undoZipPredictor(inflated.data(), lines.data(), rawSize, avx2);
    raw = lines.data();
  }
  const auto width = static_cast<std::size_t>(layout.width());
  [[maybe_unused]] const bool halfOrMissing = std::all_of(layout.type.begin(), layout.type.end(), [](int t) { return t == 1 || t < 0; });
  for (std::size_t line = 0; line < lineCount; ++line) {
    const uint8_t* start = raw + line * layout.bytesPerLine;
    std::array<const uint8_t*, 4> source{};
    for (std::size_t c = 0; c < 4; ++c) source[c] = layout.type[c] < 0 ? nullptr : start + layout.offset[c];
    float* out = image.rgba.data() + (static_cast<std::size_t>(y - layout.minY) + line) * width * 4;
#if FGB_EXR_F16C
    if (halfOrMissing && avx2) {
      convertHalfLineAvx2(source, layout.type, width, out);
      continue;
    }
#endif
    convertLineScalar(source, layout.type, width, out);
  }
  return true;
}

}  // namespace

std::optional<Image> readExrFast(const std::filesystem::path& path) {
  if (std::getenv("FGBENCH_EXR_OPENEXR") || !libdeflate()) return std::nullopt;
  std::vector<uint8_t> file;
  {
    std::ifstream stream(path, std::ios::binary | std::ios::ate);
    if (!stream) return std::nullopt;
    const std::streamsize size = stream.tellg();
    if (size <= 0) return std::nullopt;
    file = zeroFilledBytes(static_cast<std::size_t>(size));  // huge pages: tens of MB for a noisy 4K image
    stream.seekg(0);
    if (!stream.read(reinterpret_cast<char*>(file.data()), size)) return std::nullopt;
  }
  const std::optional<ExrLayout> layout = parseSimpleExr(file);
  if (!layout) return std::nullopt;
  Image image = makeImage(static_cast<uint32_t>(layout->width()), static_cast<uint32_t>(layout->height()), Encoding::Linear);
  // Chunks handed out one by one: ZIP blocks differ a lot in how long they take to inflate.
  const std::size_t chunks = layout->chunkOffsets.size();
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  const bool avx2 = useAvx2();
  parallelFor(std::min<std::size_t>(workerCount(), chunks), 1, [&](std::size_t, std::size_t) {
    const Libdeflate& deflate = *libdeflate();
    const std::unique_ptr<void, Libdeflate::Free> decompressor(deflate.alloc(), deflate.release);
    if (!decompressor) {
      failed = true;
      return;
    }
    std::vector<uint8_t> inflated, lines;
    for (std::size_t chunk = next++; chunk < chunks && !failed; chunk = next++) {
      if (!decodeChunk(file, *layout, chunk, decompressor.get(), avx2, inflated, lines, image)) failed = true;
    }
  });
  if (failed) return std::nullopt;
  return image;
}

}  // namespace fgb::harness::detail
