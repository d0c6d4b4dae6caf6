// rcsplat's own EXR writer and reader, for builds without OpenImageIO. The layout follows the OpenEXR file-layout
// document: magic and version, a header of (name, type, size, value) attributes ending in a zero byte, a table of
// scanline offsets, then one block per scanline (y, byte count, each channel's row in turn). All little-endian.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <vector>

#include "image/exr_file.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr uint32_t kMagic = 20000630;
constexpr uint32_t kLongNamesFlag = 0x400;
constexpr uint32_t kUnsupportedFlags = 0x200 | 0x800 | 0x1000;  // tiled, deep data, multi-part
constexpr int32_t kFloatPixels = 2;
constexpr size_t kShortNameLimit = 31;

class ByteWriter {
 public:
  template <class T>
  void value(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // x86-64 and Arm hosts are little-endian, as the format is
    bytes.append(b, sizeof(T));
  }
  void text(const std::string& s) { bytes.append(s).push_back('\0'); }
  void attribute(const std::string& name, const std::string& type, const std::string& value) {
    text(name);
    text(type);
    this->value(int32_t(value.size()));
    bytes.append(value);
  }
  std::string bytes;
};

class ByteReader {
 public:
  ByteReader(const std::string& path, const std::string& data) : path_(path), data_(data.begin(), data.end()) {}
  template <class T>
  T value() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::string text() {
    auto end = std::find(data_.begin() + std::ptrdiff_t(at_), data_.end(), '\0');
    if (end == data_.end()) fail("a name runs past the end of the file");
    std::string s(data_.begin() + std::ptrdiff_t(at_), end);
    at_ = size_t(end - data_.begin()) + 1;
    return s;
  }
  std::string bytes(size_t n) {
    need(n);
    std::string s(data_.data() + at_, n);
    at_ += n;
    return s;
  }
  void seek(uint64_t offset) {
    if (offset > data_.size()) fail("a scanline offset points past the end of the file");
    at_ = size_t(offset);
  }
  size_t remaining() const { return data_.size() - at_; }
  [[noreturn]] void fail(const std::string& why) const { throw Error(path_ + ": not a readable EXR file: " + why); }

 private:
  void need(size_t n) const {
    if (n > data_.size() - at_) fail("it ends early (truncated?)");
  }
  std::string path_;
  std::vector<char> data_;
  size_t at_ = 0;
};

std::string box(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  ByteWriter w;
  for (int32_t v : {x0, y0, x1, y1}) w.value(v);
  return w.bytes;
}

}  // namespace

void write_uncompressed_exr(const std::string& path, const ExrPixels& image) {
  size_t n_channels = image.channels.size();
  size_t pixels = size_t(image.width) * size_t(image.height);
  if (image.width <= 0 || image.height <= 0 || n_channels == 0 || image.values.size() != pixels * n_channels)
    throw Error(path + ": image size does not match its pixels");
  // The format stores channels sorted by name.
  std::vector<size_t> order(n_channels);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return image.channels[a] < image.channels[b]; });

  bool long_names = false;
  ByteWriter channel_list;
  for (size_t c : order) {
    long_names |= image.channels[c].size() > kShortNameLimit;
    channel_list.text(image.channels[c]);
    channel_list.value(kFloatPixels);
    channel_list.value(uint32_t(0));  // pLinear and three reserved bytes
    channel_list.value(int32_t(1));   // x sampling
    channel_list.value(int32_t(1));   // y sampling
  }
  channel_list.bytes.push_back('\0');
  for (const auto& [name, value] : image.text) long_names |= name.size() > kShortNameLimit;

  ByteWriter file;
  file.value(kMagic);
  file.value(uint32_t(2) | (long_names ? kLongNamesFlag : 0u));
  std::string window = box(0, 0, image.width - 1, image.height - 1);
  ByteWriter one, centre;
  one.value(1.0f);
  centre.value(0.0f);
  centre.value(0.0f);
  file.attribute("channels", "chlist", channel_list.bytes);
  file.attribute("compression", "compression", std::string(1, '\0'));
  file.attribute("dataWindow", "box2i", window);
  file.attribute("displayWindow", "box2i", window);
  file.attribute("lineOrder", "lineOrder", std::string(1, '\0'));  // increasing y
  file.attribute("pixelAspectRatio", "float", one.bytes);
  file.attribute("screenWindowCenter", "v2f", centre.bytes);
  file.attribute("screenWindowWidth", "float", one.bytes);
  for (const auto& [name, value] : image.text) file.attribute(name, "string", value);
  file.bytes.push_back('\0');

  size_t row_bytes = size_t(image.width) * n_channels * sizeof(float);
  uint64_t block_start = file.bytes.size() + size_t(image.height) * sizeof(uint64_t);
  for (int y = 0; y < image.height; ++y) file.value(uint64_t(block_start + size_t(y) * (8 + row_bytes)));
  for (int y = 0; y < image.height; ++y) {
    file.value(int32_t(y));
    file.value(int32_t(row_bytes));
    const float* row = image.values.data() + size_t(y) * size_t(image.width) * n_channels;
    for (size_t c : order)
      for (int x = 0; x < image.width; ++x) file.value(row[size_t(x) * n_channels + c]);
  }
  write_file_atomically(path, [&](const std::string& temp) -> std::string {
    std::ofstream out(temp, std::ios::binary);
    out.write(file.bytes.data(), std::streamsize(file.bytes.size()));
    out.close();
    return out ? "" : "writing failed";
  });
}

ExrPixels read_uncompressed_exr(const std::string& path, bool with_pixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot be read");
  std::ostringstream contents;
  contents << in.rdbuf();
  ByteReader r(path, contents.str());
  if (r.value<uint32_t>() != kMagic) r.fail("no EXR magic number");
  uint32_t version = r.value<uint32_t>();
  if ((version & 0xff) != 2 || (version & kUnsupportedFlags))
    r.fail("only single-part scanline files are supported without OpenImageIO");

  ExrPixels image;
  bool have_window = false, have_channels = false;
  int32_t x0 = 0, y0 = 0;
  for (std::string name = r.text(); !name.empty(); name = r.text()) {
    std::string type = r.text();
    int32_t size = r.value<int32_t>();
    if (size < 0) r.fail("attribute " + name + " has a negative size");
    ByteReader value(path, r.bytes(size_t(size)));
    if (name == "channels") {
      for (std::string channel = value.text(); !channel.empty(); channel = value.text()) {
        if (value.value<int32_t>() != kFloatPixels)
          r.fail("channel " + channel + " is not 32-bit float (only float channels are supported without OpenImageIO)");
        value.bytes(12);  // pLinear, reserved, sampling
        image.channels.push_back(channel);
      }
      have_channels = true;
    } else if (name == "compression") {
      if (value.value<uint8_t>() != 0) r.fail("compressed (only uncompressed files are supported without OpenImageIO)");
    } else if (name == "dataWindow") {
      x0 = value.value<int32_t>();
      y0 = value.value<int32_t>();
      int64_t w = int64_t(value.value<int32_t>()) - x0 + 1, h = int64_t(value.value<int32_t>()) - y0 + 1;
      if (w <= 0 || h <= 0 || w > 65536 || h > 65536) r.fail("invalid data window");
      image.width = int(w);
      image.height = int(h);
      have_window = true;
    } else if (type == "string") {
      image.text[name] = value.bytes(size_t(size));
    }
  }
  if (!have_window || !have_channels || image.channels.empty()) r.fail("no channels or no data window in the header");
  if (!with_pixels) return image;

  size_t n_channels = image.channels.size();
  size_t row_floats = size_t(image.width) * n_channels;
  // Checked before allocating: a damaged header must not ask for gigabytes.
  if (r.remaining() / size_t(image.height) < 16 + row_floats * sizeof(float))
    r.fail("the file is smaller than its header says (truncated?)");
  image.values.assign(row_floats * size_t(image.height), 0.0f);
  std::vector<uint64_t> offsets(size_t(image.height));
  for (uint64_t& o : offsets) o = r.value<uint64_t>();
  for (uint64_t offset : offsets) {
    r.seek(offset);
    int64_t y = int64_t(r.value<int32_t>()) - y0;
    if (y < 0 || y >= image.height) r.fail("a scanline lies outside the data window");
    if (r.value<int32_t>() != int32_t(row_floats * sizeof(float))) r.fail("a scanline has the wrong size");
    float* row = image.values.data() + size_t(y) * row_floats;
    for (size_t c = 0; c < n_channels; ++c)
      for (int x = 0; x < image.width; ++x) row[size_t(x) * n_channels + c] = r.value<float>();
  }
  return image;
}

}  // namespace rcsplat
