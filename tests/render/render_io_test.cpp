// Rendering infrastructure: EXR and PNG I/O, whole-or-nothing writes, the OpenMP image loop, the progress bar.
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/render/progress_bar.hpp"

#include <Imath/half.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace render_io_test {

namespace fs = std::filesystem;
using grtrace::Image;
using grtrace::PixelSample;
using grtrace::RayStatus;

/// A fresh empty directory per test, removed afterwards. (Outside the anonymous namespace: the tests derived from it
/// live in this file's named one.)
class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("grtrace_render_io_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    for (auto& entry : fs::directory_iterator(dir_, ec)) fs::permissions(entry.path(), fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
  }
  /// Names of everything in the directory (to check that no temporary was left behind).
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

namespace {

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }
float from_bits(std::uint32_t u) { return std::bit_cast<float>(u); }

void expect_channels_bit_identical(const Image& a, const Image& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.channel_names(), b.channel_names());
  for (const auto& name : a.channel_names()) {
    const auto& ca = a.channel(name);
    const auto& cb = b.channel(name);
    ASSERT_EQ(ca.size(), cb.size()) << name;
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < ca.size(); ++i)
      if (bits(ca[i]) != bits(cb[i])) ++mismatches;
    EXPECT_EQ(mismatches, 0u) << "channel " << name;
  }
}

/// An image whose channels hold awkward values: NaN with payloads, infinities, -0, denormals, extremes.
Image awkward_image(int w, int h) {
  Image image(w, h);
  image.add_channel("error");
  const std::vector<float> specials = {0.0f,
                                       -0.0f,
                                       1.0f,
                                       -1.0f,
                                       0.5f,
                                       std::numeric_limits<float>::quiet_NaN(),
                                       from_bits(0x7fc01234u),
                                       from_bits(0xffc00001u),
                                       std::numeric_limits<float>::infinity(),
                                       -std::numeric_limits<float>::infinity(),
                                       std::numeric_limits<float>::denorm_min(),
                                       std::numeric_limits<float>::max(),
                                       std::numeric_limits<float>::lowest(),
                                       3.14159265f,
                                       1e-30f,
                                       6.02e23f};
  std::size_t k = 0;
  for (const auto& name : image.channel_names()) {
    auto& c = image.channel(name);
    for (std::size_t i = 0; i < c.size(); ++i, ++k) c[i] = specials[(k * 7 + i / 3) % specials.size()];
  }
  return image;
}

}  // namespace

// ---- Image ---------------------------------------------------------------------------------------------

TEST(Image, SetAndSampleRoundTrip) {
  Image image(4, 3);
  PixelSample s;
  s.rgb = {0.25f, 0.5f, 2.0f};
  s.object = 2;  // the first of the scene's own objects
  s.status = RayStatus::hit;
  s.redshift = 1.5f;
  s.sky_theta = 0.1f;
  s.sky_phi = -0.2f;
  s.steps = 321;
  s.order = 2;
  image.set(3, 2, s);
  const PixelSample t = image.sample(3, 2);
  EXPECT_EQ(t.rgb, s.rgb);
  EXPECT_EQ(t.object, s.object);
  EXPECT_EQ(t.status, s.status);
  EXPECT_EQ(t.redshift, s.redshift);
  EXPECT_EQ(t.sky_theta, s.sky_theta);
  EXPECT_EQ(t.sky_phi, s.sky_phi);
  EXPECT_EQ(t.steps, s.steps);
  EXPECT_EQ(t.order, s.order);
  EXPECT_EQ(image.channel("status")[image.index(3, 2)], 2.0f);
}

TEST(Image, WithChannelsHasExactlyThose) {
  const Image image = Image::with_channels(2, 2, {"R", "G", "B", "A", "G"}, 1.0f);
  EXPECT_EQ(image.channel_names(), (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_FALSE(image.has_channel("status"));
  EXPECT_EQ(image.channel("A")[3], 1.0f);
  Image copy = image;
  EXPECT_THROW(copy.set(0, 0, PixelSample{}), std::out_of_range);
  EXPECT_THROW(Image::with_channels(0, 2, {"R"}), std::invalid_argument);
}

// ---- whole-or-nothing writes -----------------------------------------------------------------------------

using AtomicWrite = TempDir;

TEST_F(AtomicWrite, FailingWriterLeavesOldFileAndNoTemporary) {
  const fs::path target = dir_ / "out.txt";
  { std::ofstream(target) << "old"; }
  EXPECT_THROW(grtrace::write_file_atomically(target,
                                              [](std::ostream& out) {
                                                out << "partial";
                                                throw std::runtime_error("disk on fire");
                                              }),
               std::runtime_error);
  EXPECT_EQ(listing(), std::vector<std::string>{"out.txt"});
  std::ifstream in(target);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "old");
}

TEST_F(AtomicWrite, ReplacesExistingFile) {
  const fs::path target = dir_ / "out.txt";
  { std::ofstream(target) << "old"; }
  grtrace::write_file_atomically(target, [](std::ostream& out) { out << "new"; });
  std::ifstream in(target);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "new");
  EXPECT_EQ(listing(), std::vector<std::string>{"out.txt"});
}

// ---- EXR -----------------------------------------------------------------------------------------------

using Exr = TempDir;

TEST_F(Exr, RoundTripIsBitExactForEveryChannelAndCompression) {
  const Image image = awkward_image(13, 7);
  for (const auto compression : {Imf::NO_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION}) {
    SCOPED_TRACE(static_cast<int>(compression));
    const fs::path path = dir_ / "frame.exr";
    grtrace::write_exr(path, image, {.compression = compression});
    const Image back = grtrace::read_exr(path);
    expect_channels_bit_identical(image, back);
    // the NaN payloads in particular (bit-identical above; here: there were some to compare)
    const auto& r = back.channel("R");
    EXPECT_GT(std::count_if(r.begin(), r.end(), [](float v) { return std::isnan(v); }), 0);
    EXPECT_GT(std::count_if(r.begin(), r.end(), [](float v) { return bits(v) == 0x7fc01234u; }), 0);
  }
  EXPECT_EQ(listing(), std::vector<std::string>{"frame.exr"});
}

// Every compression the tools offer by name, at both ends of the zlib levels, in the calling thread and on a pool
// (with a frame tall enough for several chunks of every compression): the same bits back, the compression asked.
TEST_F(Exr, NamedCompressionsLevelsAndThreadsAllReadBackBitExact) {
  const Image image = awkward_image(37, 77);
  for (const auto& [name, compression] : grtrace::kExrLosslessCompressions)
    for (const int level : {1, 9, -1})
      for (const int threads : {1, 2, 0}) {
        SCOPED_TRACE(std::string(name) + " level " + std::to_string(level) + " threads " + std::to_string(threads));
        const fs::path path = dir_ / "frame.exr";
        grtrace::write_exr(path, image, {.compression = compression, .zip_level = level, .threads = threads});
        expect_channels_bit_identical(image, grtrace::read_exr(path));
        EXPECT_EQ(Imf::InputFile(path.c_str()).header().compression(), compression);
      }
  EXPECT_EQ(listing(), std::vector<std::string>{"frame.exr"});
}

TEST(ExrNames, OnlyTheLosslessCompressionsHaveNames) {
  EXPECT_EQ(grtrace::exr_compression_from_name("zip"), Imf::ZIP_COMPRESSION);
  EXPECT_EQ(grtrace::exr_compression_from_name("zips"), Imf::ZIPS_COMPRESSION);
  EXPECT_EQ(grtrace::exr_compression_from_name("piz"), Imf::PIZ_COMPRESSION);
  EXPECT_EQ(grtrace::exr_compression_from_name("rle"), Imf::RLE_COMPRESSION);
  EXPECT_EQ(grtrace::exr_compression_from_name("none"), Imf::NO_COMPRESSION);
  for (const char* lossy : {"pxr24", "b44", "b44a", "dwaa", "dwab", "ZIP", "", "zip1"})
    EXPECT_FALSE(grtrace::exr_compression_from_name(lossy).has_value()) << lossy;
}

TEST_F(Exr, ZipLevelOutsideOneToNineIsRefusedAndNothingIsWritten) {
  for (const int level : {0, 10, -2})
    EXPECT_THROW(grtrace::write_exr(dir_ / "frame.exr", Image(2, 2), {.zip_level = level}), std::invalid_argument);
  EXPECT_TRUE(listing().empty());
}

// ZIP, ZIPS and uncompressed files are laid out by grtrace itself (exr_io.hpp write_exr_scanlines) and deflated by
// libdeflate: OpenEXR must read every chunk back, including chunks that do not compress (random bits: stored
// raw, which a reader recognises by their size) next to chunks that do, a last chunk shorter than the others, and
// names longer than 31 characters (the version's long-names flag). OpenEXR's own ZIP writer, given the same image,
// produces a file that reads back to the same bits.
TEST_F(Exr, GrtraceWrittenChunksReadBackInOpenExr) {
  Image image(29, 37);  // 37 lines: two full ZIP chunks of 16 and one of 5
  image.add_channel("a_channel_name_longer_than_31_characters");
  image.metadata["an_attribute_name_longer_than_31_characters"] = "long names";
  std::uint32_t state = 12345u;
  std::size_t channel_index = 0;
  for (const auto& name : image.channel_names()) {
    auto& c = image.channel(name);
    for (std::size_t i = 0; i < c.size(); ++i) {
      state = state * 1664525u + 1013904223u;  // random bits in the even channels, smooth values in the odd ones
      c[i] = channel_index % 2 == 0 ? from_bits(state) : static_cast<float>(i % 97) * 0.25f;
    }
    ++channel_index;
  }
  for (const auto compression : {Imf::NO_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::ZIPS_COMPRESSION}) {
    SCOPED_TRACE(static_cast<int>(compression));
    ASSERT_TRUE(grtrace::detail::exr_written_by_grtrace(compression));
    const fs::path path = dir_ / "frame.exr";
    grtrace::write_exr(path, image, {.compression = compression, .threads = 3});
    const Imf::InputFile file(path.c_str());
    EXPECT_EQ(file.header().compression(), compression);
    EXPECT_TRUE(file.isComplete());
    const Image back = grtrace::read_exr(path);
    expect_channels_bit_identical(image, back);
    EXPECT_EQ(back.metadata.at("an_attribute_name_longer_than_31_characters"), "long names");
  }
  // Random bits do not deflate: a chunk of only random bits is stored raw, and still reads back.
  Image noise(16, 3);
  for (const auto& name : noise.channel_names())
    for (float& v : noise.channel(name)) v = from_bits(state = state * 1664525u + 1013904223u);
  grtrace::write_exr(dir_ / "noise.exr", noise, {.compression = Imf::ZIPS_COMPRESSION});
  expect_channels_bit_identical(noise, grtrace::read_exr(dir_ / "noise.exr"));
}

TEST_F(Exr, AttributesRoundTrip) {
  Image image(3, 2);
  image.metadata["camera_r"] = "20";
  image.metadata["metric"] = "schwarzschild";
  image.metadata["command_line"] = "grtrace-render --scene checker --fov 90 --out \"a b.exr\"";
  image.metadata["empty"] = "";
  image.metadata["unicode"] = "θ, φ in radians — ∞";
  image.metadata["long"] = std::string(5000, 'x');
  const fs::path path = dir_ / "meta.exr";
  grtrace::write_exr(path, image);
  const Image back = grtrace::read_exr(path);
  for (const auto& [key, value] : image.metadata) {
    ASSERT_TRUE(back.metadata.count(key)) << key;
    EXPECT_EQ(back.metadata.at(key), value) << key;
  }
  // the extras that make a file self-describing
  EXPECT_EQ(back.metadata.at("software"), "grtrace");
  EXPECT_EQ(back.metadata.at("status_names"), "0=escaped 1=captured 2=hit 3=max_steps 4=step_underflow 5=non_finite");
  EXPECT_EQ(back.metadata.at("object_names"), "0=sky 1=horizon 2=disk 3=star");
  // user values win over the extras, and a second round trip is stable
  Image again = back;
  again.metadata["software"] = "my tool";
  grtrace::write_exr(path, again);
  EXPECT_EQ(grtrace::read_exr(path).metadata, again.metadata);
}

TEST_F(Exr, NonGrtraceChannelsReadInStandardThenAlphabeticalOrder) {
  Image texture = Image::with_channels(5, 4, {"A", "B", "G", "R", "Z"});
  for (std::size_t i = 0; i < texture.pixel_count(); ++i) texture.channel("G")[i] = static_cast<float>(i);
  const fs::path path = dir_ / "texture.exr";
  grtrace::write_exr(path, texture);
  const Image back = grtrace::read_exr(path);
  EXPECT_EQ(back.channel_names(), (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
  EXPECT_EQ(back.channel("G")[19], 19.0f);
  EXPECT_FALSE(back.has_channel("status"));
  EXPECT_EQ(back.metadata.count("status_names"), 0u);
}

TEST_F(Exr, ReadsOffsetDataWindowsAndHalfChannels) {
  // A file written by another program: data window not at the origin, a HALF channel and a FLOAT one.
  const Imath::Box2i window(Imath::V2i(-3, 5), Imath::V2i(2, 8));  // 6 x 4
  Imf::Header header(window, window);
  header.channels().insert("Y", Imf::Channel(Imf::HALF));
  header.channels().insert("depth", Imf::Channel(Imf::FLOAT));
  std::vector<Imath::half> y(24);
  std::vector<float> depth(24);
  for (std::size_t i = 0; i < 24; ++i) {
    y[i] = Imath::half(0.25f * static_cast<float>(i));
    depth[i] = 100.0f + static_cast<float>(i);
  }
  const fs::path path = dir_ / "foreign.exr";
  {
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice::Make(Imf::HALF, y.data(), window));
    frame.insert("depth", Imf::Slice::Make(Imf::FLOAT, depth.data(), window));
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(4);
  }
  const Image back = grtrace::read_exr(path);
  EXPECT_EQ(back.width(), 6);
  EXPECT_EQ(back.height(), 4);
  EXPECT_EQ(back.channel_names(), (std::vector<std::string>{"Y", "depth"}));
  EXPECT_EQ(back.channel("Y")[back.index(5, 3)], 0.25f * 23.0f);
  EXPECT_EQ(back.channel("depth")[back.index(1, 2)], 113.0f);
}

TEST_F(Exr, WriteIntoMissingDirectoryThrowsAndLeavesNothing) {
  const fs::path path = dir_ / "no" / "such" / "dir" / "frame.exr";
  try {
    grtrace::write_exr(path, Image(2, 2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(Exr, WriteBelowARegularFileThrowsAndLeavesNothing) {
  { std::ofstream(dir_ / "file") << "x"; }
  EXPECT_THROW(grtrace::write_exr(dir_ / "file" / "frame.exr", Image(2, 2)), std::runtime_error);
  EXPECT_EQ(listing(), std::vector<std::string>{"file"});
}

TEST_F(Exr, WriteOverADirectoryThrowsAndLeavesItAlone) {
  fs::create_directory(dir_ / "frame.exr");
  EXPECT_THROW(grtrace::write_exr(dir_ / "frame.exr", Image(2, 2)), std::runtime_error);
  EXPECT_EQ(listing(), std::vector<std::string>{"frame.exr"});
  EXPECT_TRUE(fs::is_directory(dir_ / "frame.exr"));
}

TEST_F(Exr, WriteIntoUnwritableDirectoryThrowsAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  try {
    grtrace::write_exr(locked / "frame.exr", Image(2, 2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not writable"), std::string::npos) << e.what();
  }
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(locked));
}

TEST_F(Exr, MetadataKeyCollidingWithRequiredAttributeIsRefused) {
  Image image(2, 2);
  image.metadata["dataWindow"] = "0 0 1 1";
  EXPECT_THROW(grtrace::write_exr(dir_ / "frame.exr", image), std::invalid_argument);
  image.metadata.clear();
  image.metadata[""] = "nameless";
  EXPECT_THROW(grtrace::write_exr(dir_ / "frame.exr", image), std::invalid_argument);
  EXPECT_TRUE(listing().empty());
}

TEST_F(Exr, ReadingMissingOrCorruptFilesThrows) {
  EXPECT_THROW(grtrace::read_exr(dir_ / "missing.exr"), std::runtime_error);
  { std::ofstream(dir_ / "text.exr") << "this is not an EXR file"; }
  EXPECT_THROW(grtrace::read_exr(dir_ / "text.exr"), std::runtime_error);
  // a truncated real file
  grtrace::write_exr(dir_ / "full.exr", awkward_image(32, 32));
  fs::resize_file(dir_ / "full.exr", fs::file_size(dir_ / "full.exr") / 2);
  EXPECT_THROW(grtrace::read_exr(dir_ / "full.exr"), std::runtime_error);
}

// ---- PNG -----------------------------------------------------------------------------------------------

TEST(Srgb, KnownValues) {
  EXPECT_EQ(grtrace::srgb_encode8(0.0), 0);
  EXPECT_EQ(grtrace::srgb_encode8(1.0), 255);
  EXPECT_EQ(grtrace::srgb_encode8(0.5), 188);
  EXPECT_EQ(grtrace::srgb_encode8(0.18), 118);
  EXPECT_EQ(grtrace::srgb_encode8(0.0031308 / 2), 5);  // linear segment: 12.92 * 0.0015654 * 255 = 5.16
  EXPECT_EQ(grtrace::srgb_encode8(-1.0), 0);
  EXPECT_EQ(grtrace::srgb_encode8(7.0), 255);
  EXPECT_EQ(grtrace::srgb_encode8(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(grtrace::srgb_encode8(std::numeric_limits<double>::infinity()), 255);
  // every code survives decode -> encode
  for (int c = 0; c < 256; ++c)
    EXPECT_EQ(grtrace::srgb_encode8(grtrace::srgb_decode8(static_cast<std::uint8_t>(c))), c) << c;
}

// The preview encodes with a table of thresholds instead of pow (png_preview.hpp): the same code for every value.
// (Checked once for every float in [0, 1.5) when it was written; here: the doubles around each threshold, the
// extremes, and a million random values over the whole range the preview sees.)
TEST(Srgb, ThresholdTableEncodesLikeTheTransferFunction) {
  const auto& t = grtrace::detail::srgb_encode8_thresholds();
  auto same = [&](double x) {
    EXPECT_EQ(grtrace::detail::srgb_encode8_fast(x, t), grtrace::srgb_encode8(x)) << std::hexfloat << x;
  };
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(static_cast<std::size_t>(grtrace::srgb_encode8(t[k])), k + 1);
    EXPECT_EQ(static_cast<std::size_t>(grtrace::srgb_encode8(std::nextafter(t[k], 0.0))), k);
    for (const double x : {std::nextafter(t[k], 0.0), t[k], std::nextafter(t[k], 2.0)}) same(x);
  }
  for (const double x : {0.0, -0.0, -1.0, 1.0, std::nextafter(1.0, 0.0), 1e-300, 5e-324, 7.0,
                         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN()})
    same(x);
  std::uint64_t state = 0x9e3779b97f4a7c15u;  // splitmix64
  for (int i = 0; i < 1'000'000; ++i) {
    state += 0x9e3779b97f4a7c15u;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    const double u = static_cast<double>(z >> 11) * 0x1.0p-53;  // [0, 1)
    const double x = i % 2 == 0 ? u * 1.2 : std::pow(10.0, -12.0 * u);  // linear and logarithmic coverage
    if (grtrace::detail::srgb_encode8_fast(x, t) != grtrace::srgb_encode8(x)) same(x);  // reports only failures
  }
}

using Png = TempDir;

// The writer uses libpng's full API now: the file still carries its sRGB chunk and reads back exactly.
TEST_F(Png, WrittenFileHasTheSrgbChunkAndReadsBackExactly) {
  const int w = 61, h = 29;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(3 * w * h));
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>((i * 37u) ^ (i >> 5));
  const fs::path path = dir_ / "map.png";
  grtrace::write_png_rgb8(path, w, h, rgb);
  std::string bytes(fs::file_size(path), '\0');
  std::ifstream(path, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_NE(bytes.find("sRGB"), std::string::npos);
  EXPECT_NE(bytes.find("IEND"), std::string::npos);
  EXPECT_EQ(grtrace::read_png_rgb8(path).rgb, rgb);
}

TEST_F(Png, PreviewEncodesLinearValuesAsSrgb) {
  Image image(3, 2);
  const float values[6][3] = {{0.0f, 1.0f, 0.5f}, {0.18f, 2.0f, -1.0f}, {0.25f, 0.25f, 0.25f},
                              {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},   {0.0f, 0.0f, 1.0f}};
  for (int i = 0; i < 6; ++i) {
    PixelSample s;
    s.rgb = {values[i][0], values[i][1], values[i][2]};
    image.set(i % 3, i / 3, s);
  }
  const fs::path path = dir_ / "preview.png";
  grtrace::write_png_preview(path, image);
  const grtrace::PngRgb8 png = grtrace::read_png_rgb8(path);
  ASSERT_EQ(png.width, 3);
  ASSERT_EQ(png.height, 2);
  const std::vector<std::uint8_t> expected = {0, 255, 188, 118, 255, 0, 137, 137, 137, 255, 0, 0, 0, 255, 0, 0, 0, 255};
  EXPECT_EQ(png.rgb, expected);

  grtrace::write_png_preview(path, image, 2.0f);  // 0.25 * 2 = 0.5 -> 188
  EXPECT_EQ(grtrace::read_png_rgb8(path).rgb[6], 188);
  EXPECT_EQ(listing(), std::vector<std::string>{"preview.png"});
}

TEST_F(Png, Rgb8RoundTripIsExact) {
  const int w = 37;
  const int h = 11;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(3 * w * h));
  std::uint32_t state = 12345;
  for (auto& byte : rgb) {
    state = state * 1664525u + 1013904223u;
    byte = static_cast<std::uint8_t>(state >> 24);
  }
  grtrace::write_png_rgb8(dir_ / "noise.png", w, h, rgb);
  const auto png = grtrace::read_png_rgb8(dir_ / "noise.png");
  EXPECT_EQ(png.width, w);
  EXPECT_EQ(png.height, h);
  EXPECT_EQ(png.rgb, rgb);
}

TEST_F(Png, BadArgumentsAndFailingWritesThrowAndLeaveNothing) {
  EXPECT_THROW(grtrace::write_png_rgb8(dir_ / "a.png", 2, 2, std::vector<std::uint8_t>(11)), std::invalid_argument);
  EXPECT_THROW(grtrace::write_png_rgb8(dir_ / "a.png", 0, 2, {}), std::invalid_argument);
  EXPECT_THROW(grtrace::write_png_preview(dir_ / "a.png", Image(2, 2), -1.0f), std::invalid_argument);
  EXPECT_THROW(grtrace::write_png_preview(dir_ / "a.png", Image::with_channels(2, 2, {"R", "G"})),
               std::invalid_argument);
  EXPECT_THROW(grtrace::write_png_preview(dir_ / "missing" / "a.png", Image(2, 2)), std::runtime_error);
  EXPECT_TRUE(listing().empty());
  EXPECT_THROW(grtrace::read_png_rgb8(dir_ / "missing.png"), std::runtime_error);
  { std::ofstream(dir_ / "text.png") << "not a png"; }
  EXPECT_THROW(grtrace::read_png_rgb8(dir_ / "text.png"), std::runtime_error);
}

// ---- render_image --------------------------------------------------------------------------------------

namespace {

/// Per-thread state that notices sharing: it remembers the OpenMP thread that first used it.
struct CheckedScratch {
  std::vector<double> buffer = std::vector<double>(64);
  int owner = -1;
  long calls = 0;
  bool shared = false;
  std::mutex not_movable;  // the renderer must build scratch in place
};

/// Deterministic, unevenly expensive: cost depends strongly on the pixel (like rays near the photon ring).
PixelSample uneven_pixel(int x, int y, CheckedScratch& scratch) {
  const int me = omp_get_thread_num();
  if (scratch.owner < 0) scratch.owner = me;
  if (scratch.owner != me) scratch.shared = true;
  ++scratch.calls;
  std::fill(scratch.buffer.begin(), scratch.buffer.end(), 0.0);  // a result may depend only on (x, y)
  const auto hash = static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u;
  const int cost = static_cast<int>(hash % 3000u) + ((x - 20) * (x - 20) + (y - 12) * (y - 12) < 40 ? 20000 : 0);
  double acc = 0.0;
  for (int i = 0; i < cost; ++i) {
    scratch.buffer[static_cast<std::size_t>(i) % scratch.buffer.size()] = acc;
    acc = std::sin(acc + 0.001 * i) + 0.5 * scratch.buffer[static_cast<std::size_t>(i * 7) % scratch.buffer.size()];
  }
  PixelSample s;
  s.rgb = {static_cast<float>(acc), static_cast<float>(x) / 40.0f, static_cast<float>(y) / 25.0f};
  s.status = static_cast<RayStatus>(hash % grtrace::kRayStatusCount);
  s.object = static_cast<int>(hash % 3u);
  s.redshift = s.status == RayStatus::escaped ? static_cast<float>(acc * 0.1) : PixelSample::nan;
  s.steps = cost;
  return s;
}

constexpr int kW = 41;
constexpr int kH = 25;

}  // namespace

using Render = TempDir;

TEST_F(Render, OneAndTwoThreadsGiveIdenticalPixelsAndCounts) {
  std::array<long, grtrace::kRayStatusCount> expected_counts{};
  long expected_steps = 0;
  {
    CheckedScratch scratch;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const PixelSample s = uneven_pixel(x, y, scratch);
        ++expected_counts[static_cast<std::size_t>(s.status)];
        expected_steps += s.steps;
      }
  }

  std::atomic<int> factory_calls{0};
  std::atomic<bool> shared{false};
  auto render = [&](const grtrace::RenderOptions& options) {
    Image image(kW, kH);
    factory_calls = 0;
    const auto stats = grtrace::render_image(
        image,
        [&] {
          ++factory_calls;
          return CheckedScratch{};
        },
        [&](int x, int y, CheckedScratch& scratch) {
          PixelSample s = uneven_pixel(x, y, scratch);
          if (scratch.shared) shared = true;
          return s;
        },
        options);
    return std::pair{std::move(image), stats};
  };

  grtrace::RenderOptions one;
  one.threads = 1;
  one.progress = grtrace::ProgressMode::never;
  auto [image1, stats1] = render(one);
  EXPECT_EQ(factory_calls.load(), 1);
  EXPECT_EQ(stats1.threads, 1);

  grtrace::RenderOptions two = one;
  two.threads = 2;
  auto [image2, stats2] = render(two);
  EXPECT_EQ(factory_calls.load(), 2);
  EXPECT_EQ(stats2.threads, 2);
  EXPECT_FALSE(shared.load()) << "a scratch object was used by two threads";

  grtrace::RenderOptions rows = two;
  rows.tile_width = 0;
  rows.tile_height = 1;
  auto [image_rows, stats_rows] = render(rows);
  grtrace::RenderOptions odd_tiles = two;
  odd_tiles.tile_width = 7;
  odd_tiles.tile_height = 3;
  odd_tiles.threads = 3;
  auto [image_odd, stats_odd] = render(odd_tiles);

  expect_channels_bit_identical(image1, image2);
  expect_channels_bit_identical(image1, image_rows);
  expect_channels_bit_identical(image1, image_odd);
  for (const auto* stats : {&stats1, &stats2, &stats_rows, &stats_odd}) {
    EXPECT_EQ(stats->width, kW);
    EXPECT_EQ(stats->height, kH);
    EXPECT_EQ(stats->rays, long{kW} * kH);
    EXPECT_EQ(stats->status_counts, expected_counts);
    EXPECT_EQ(stats->total_steps, expected_steps);
    EXPECT_EQ(stats->bad_colour, 0);
    EXPECT_DOUBLE_EQ(stats->mean_steps, static_cast<double>(expected_steps) / (kW * kH));
    EXPECT_GT(stats->seconds, 0.0);
    EXPECT_GT(stats->rays_per_second, 0.0);
  }
  // the status channel agrees with the counts
  std::array<long, grtrace::kRayStatusCount> channel_counts{};
  for (float v : image2.channel("status")) ++channel_counts[static_cast<std::size_t>(v)];
  EXPECT_EQ(channel_counts, expected_counts);

  // and the EXR files written from them hold identical pixels
  grtrace::write_exr(dir_ / "one.exr", image1);
  grtrace::write_exr(dir_ / "two.exr", image2);
  expect_channels_bit_identical(grtrace::read_exr(dir_ / "one.exr"), grtrace::read_exr(dir_ / "two.exr"));
}

TEST(RenderImage, NonFiniteColourIsReplacedAndCounted) {
  Image image(10, 10);
  grtrace::RenderOptions options;
  options.threads = 2;
  options.progress = grtrace::ProgressMode::never;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const auto stats = grtrace::render_image(
      image,
      [&](int x, int y) {
        PixelSample s;
        s.status = RayStatus::escaped;
        s.rgb = {0.1f, 0.2f, 0.3f};
        s.steps = 1;
        if (y == 0) s.rgb[1] = nan;                      // 10 escaped rays with NaN colour
        if (y == 1 && x < 4) s.rgb = {inf, 0.0f, 0.0f};  // 4 more, Inf
        if (y == 2 && x < 3) {                           // 3 failed rays with NaN colour keep their status
          s.status = RayStatus::max_steps;
          s.rgb[2] = -nan;
        }
        if (y == 3 && x == 0) s.status = static_cast<RayStatus>(200);  // garbage status
        return s;
      },
      options);
  for (const char* c : {"R", "G", "B"})
    for (float v : image.channel(c)) ASSERT_TRUE(std::isfinite(v)) << c;
  EXPECT_EQ(stats.bad_colour, 17);
  EXPECT_EQ(stats.bad_status, 1);
  EXPECT_EQ(stats.count(RayStatus::non_finite), 15);
  EXPECT_EQ(stats.count(RayStatus::max_steps), 3);
  EXPECT_EQ(stats.count(RayStatus::escaped), 100 - 18);
  EXPECT_EQ(stats.failures(), 18);
  const PixelSample bad = image.sample(5, 0);
  EXPECT_EQ(bad.rgb, options.error_rgb);
  EXPECT_EQ(bad.status, RayStatus::non_finite);
  EXPECT_EQ(image.sample(1, 2).status, RayStatus::max_steps);
  EXPECT_EQ(image.sample(1, 2).rgb, options.error_rgb);
  EXPECT_EQ(image.sample(0, 3).status, RayStatus::non_finite);
  EXPECT_EQ(image.sample(0, 3).rgb, (std::array<float, 3>{0.1f, 0.2f, 0.3f}));
  EXPECT_EQ(image.sample(9, 9).status, RayStatus::escaped);
}

TEST(RenderImage, ExceptionInWorkerIsRethrownNotFatal) {
  Image image(64, 64);
  grtrace::RenderOptions options;
  options.threads = 2;
  options.tile_width = 8;
  options.tile_height = 8;
  options.progress = grtrace::ProgressMode::never;
  std::atomic<long> calls{0};
  try {
    grtrace::render_image(
        image,
        [&](int x, int y) {
          ++calls;
          if (x == 17 && y == 33) throw std::domain_error("pixel (17, 33) failed");
          return PixelSample{};
        },
        options);
    FAIL() << "no exception";
  } catch (const std::domain_error& e) {
    EXPECT_STREQ(e.what(), "pixel (17, 33) failed");
  }
  EXPECT_LT(calls.load(), 64 * 64);  // the remaining tiles were skipped

  EXPECT_THROW(grtrace::render_image(
                   image, []() -> int { throw std::runtime_error("no scratch"); },
                   [](int, int, int&) { return PixelSample{}; }, options),
               std::runtime_error);
}

TEST(RenderImage, BadOptionsAreRefused) {
  Image image(4, 4);
  auto pixel = [](int, int) { return PixelSample{}; };
  grtrace::RenderOptions options;
  options.progress = grtrace::ProgressMode::never;
  options.threads = -1;
  EXPECT_THROW(grtrace::render_image(image, pixel, options), std::invalid_argument);
  options.threads = 0;
  options.tile_height = 0;
  EXPECT_THROW(grtrace::render_image(image, pixel, options), std::invalid_argument);
  options.tile_height = 4;
  options.error_rgb[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(grtrace::render_image(image, pixel, options), std::invalid_argument);
}

TEST(RenderImage, DefaultThreadsAndStatsMetadata) {
  Image image(16, 8);
  grtrace::RenderOptions options;
  options.progress = grtrace::ProgressMode::never;
  const auto stats = grtrace::render_image(
      image,
      [](int x, int) {
        PixelSample s;
        s.status = x < 4 ? RayStatus::captured : RayStatus::escaped;
        s.steps = 10;
        return s;
      },
      options);
  EXPECT_EQ(stats.threads, omp_get_max_threads());
  EXPECT_EQ(stats.count(RayStatus::captured), 32);
  EXPECT_DOUBLE_EQ(stats.mean_steps, 10.0);
  grtrace::record_render_stats(image, stats);
  EXPECT_EQ(image.metadata.at("status_counts"),
            "{\"escaped\":96,\"captured\":32,\"hit\":0,\"max_steps\":0,\"step_underflow\":0,\"non_finite\":0}");
  EXPECT_EQ(image.metadata.at("mean_steps"), "10");
  EXPECT_TRUE(image.metadata.count("render_seconds"));
  EXPECT_TRUE(image.metadata.count("rays_per_second"));
}

// ---- progress bar --------------------------------------------------------------------------------------

namespace {
std::string read_all(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  return s;
}
}  // namespace

TEST(ProgressBar, FormatsPercentRateAndEta) {
  const std::string line = grtrace::ProgressBar::format("render", 250, 1000, 2.0, false);
  EXPECT_EQ(line, "render [#######.......................]  25.0%  125 rays/s  ETA 0:06");
  const std::string last = grtrace::ProgressBar::format("render", 1000, 1000, 0.5, true);
  EXPECT_EQ(last, "render [##############################] 100.0%  2.0k rays/s  0.50 s");
  EXPECT_EQ(grtrace::ProgressBar::format_rate(2.5e6), "2.50M");
  EXPECT_EQ(grtrace::ProgressBar::format_duration(3725.0), "1:02:05");
  EXPECT_NE(grtrace::ProgressBar::format("r", 0, 10, 0.0, false).find("ETA --:--"), std::string::npos);
}

TEST(ProgressBar, QuietWhenNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    grtrace::ProgressBar bar(100, "render", grtrace::ProgressMode::automatic, f);
    EXPECT_FALSE(bar.enabled());
    bar.advance(100);
    bar.finish();
  }
  EXPECT_EQ(read_all(f), "");
  std::fclose(f);
}

TEST(ProgressBar, ThreadSafeRateLimitedAndFinishEndsTheLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  const long per_thread = 200000;
  const auto start = std::chrono::steady_clock::now();
  {
    grtrace::ProgressBar bar(4 * per_thread, "render", grtrace::ProgressMode::always, f);
    ASSERT_TRUE(bar.enabled());
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&] {
        for (long i = 0; i < per_thread; ++i) {
          bar.advance();
          if (i % 1000 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
        }
      });
    for (auto& th : threads) th.join();
    EXPECT_EQ(bar.done(), 4 * per_thread);
    bar.finish();
    bar.finish();  // idempotent
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string out = read_all(f);
  std::fclose(f);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.back(), '\n');
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1);
  EXPECT_NE(out.find("100.0%"), std::string::npos);
  const auto redraws = std::count(out.begin(), out.end(), '\r');
  EXPECT_GE(redraws, 2);  // the 0% line and the final one at least
  EXPECT_LE(redraws, static_cast<long>(seconds * 10.0) + 3) << seconds << " s";  // at most ~10 per second
}

}  // namespace render_io_test
