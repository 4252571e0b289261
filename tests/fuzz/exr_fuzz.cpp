// Fuzz target for grtrace::read_exr (AFL++; see tests/fuzz/README.md). Each argument is a file to read; any
// exception is a refusal (fine), anything else -- a crash, an abort, a sanitizer report, a hang -- is a finding.
//   exr_fuzz FILE...              read each file (what afl-fuzz runs: exr_fuzz @@)
//   exr_fuzz --make-corpus DIR    write the seed files of tests/fuzz/corpus/exr/
#include "grtrace/render/exr_io.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <limits>
#include <string>

namespace {

void make_corpus(const std::filesystem::path& dir) {
  using namespace grtrace;
  std::filesystem::create_directories(dir);
  Image frame(5, 3);
  frame.metadata["camera_position"] = "0,50,1.5,0";
  write_exr(dir / "frame_zip.exr", frame);
  write_exr(dir / "frame_none.exr", frame, {Imf::NO_COMPRESSION});
  Image tex = Image::with_channels(6, 2, {"R", "G", "B"}, 0.25f);
  tex.channel("G")[3] = std::numeric_limits<float>::quiet_NaN();
  write_exr(dir / "texture_rle.exr", tex, {Imf::RLE_COMPRESSION});
  write_exr(dir / "texture_piz.exr", tex, {Imf::PIZ_COMPRESSION});
  // A header that claims more than the file holds: a forged 12000 x 12000 data window on a 6 x 2 texture.
  std::ifstream in(dir / "texture_rle.exr", std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string bytes = ss.str();
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  if (const auto at = bytes.find(key); at != std::string::npos) {
    const int box[4] = {0, 0, 11999, 11999};
    std::memcpy(bytes.data() + at + key.size() + 4, box, sizeof box);
    std::ofstream(dir / "forged_window.exr", std::ios::binary) << bytes;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--make-corpus") == 0) {
    make_corpus(argv[2]);
    return 0;
  }
  // Inputs claim sizes: keep what a fuzzed header may allocate well under AFL's memory limit.
  ::setenv("GRTRACE_MEMORY_LIMIT", "64M", 0);
  int refused = 0;
  for (int i = 1; i < argc; ++i) {
    try {
      const grtrace::Image image = grtrace::read_exr(argv[i]);
      volatile std::size_t sink = image.pixel_count() + image.channel_names().size();
      (void)sink;
    } catch (const std::exception&) {
      ++refused;
    }
  }
  if (std::getenv("GRTRACE_FUZZ_VERBOSE")) std::fprintf(stderr, "%d of %d refused\n", refused, argc - 1);
  return 0;
}
