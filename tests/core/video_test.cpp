#include "emoface/core/video.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

namespace fs = std::filesystem;

class VideoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!ffmpeg_available()) GTEST_SKIP() << "ffmpeg binary not installed";
    dir_ = fs::temp_directory_path() / ("emoface_video_test_" + std::string(
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  std::size_t file_count() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {})); }
  static std::vector<std::uint8_t> frame(int w, int h, int k) {
    std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        auto* p = &px[3 * (static_cast<std::size_t>(y) * w + x)];
        p[0] = static_cast<std::uint8_t>((x * 4 + k * 9) & 255);
        p[1] = static_cast<std::uint8_t>((y * 4) & 255);
        p[2] = static_cast<std::uint8_t>(k * 20 & 255);
      }
    return px;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::string write_video(const std::string& name, VideoOptions o, int frames) {
    const auto path = (dir_ / name).string();
    VideoWriter w(path, o);
    for (int k = 0; k < frames; ++k) w.add_frame(frame(o.width, o.height, k));
    EXPECT_EQ(w.frames(), static_cast<std::size_t>(frames));
    w.finish();
    return path;
  }
  fs::path dir_;
};

VideoOptions small() {
  VideoOptions o;
  o.width = 63;  // odd on purpose: padded to even for yuv420p
  o.height = 48;
  o.fps = 10;
  return o;
}

TEST_F(VideoTest, WritesMp4AtomicallyAndDeterministically) {
  const auto a = write_video("a.mp4", small(), 12);
  const auto b = write_video("b.mp4", small(), 12);
  EXPECT_EQ(file_count(), 2u);  // no temporary or log files left behind
  const std::string bytes = slurp(a);
  ASSERT_GT(bytes.size(), 100u);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp");
  EXPECT_EQ(bytes, slurp(b));
  EXPECT_NE(bytes.find("emoface"), std::string::npos);  // generator stamp in the metadata
}

TEST_F(VideoTest, FrameCountReadBackWithFfprobe) {
  const auto path = write_video("c.mkv", small(), 7);
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                          "-of csv=p=0 '" + path + "' 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  ASSERT_TRUE(p);
  char buf[64] = {};
  if (!std::fgets(buf, sizeof buf, p.get())) GTEST_SKIP() << "ffprobe not available";
  EXPECT_EQ(std::stoi(buf), 7);
}

TEST_F(VideoTest, WritesGif) {
  const auto path = write_video("d.gif", small(), 5);
  EXPECT_EQ(slurp(path).substr(0, 6), "GIF89a");
}

TEST_F(VideoTest, MuxesAudio) {
  // 1 s of 8 kHz silence, 16-bit mono PCM WAV written by hand.
  const int rate = 8000, samples = 8000;
  std::string wav = "RIFF";
  auto u32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) wav.push_back(static_cast<char>((v >> (8 * i)) & 255)); };
  auto u16 = [&](std::uint16_t v) { for (int i = 0; i < 2; ++i) wav.push_back(static_cast<char>((v >> (8 * i)) & 255)); };
  u32(36 + samples * 2);
  wav += "WAVEfmt ";
  u32(16); u16(1); u16(1); u32(rate); u32(rate * 2); u16(2); u16(16);
  wav += "data";
  u32(samples * 2);
  wav.append(samples * 2, '\0');
  std::ofstream(dir_ / "s.wav", std::ios::binary) << wav;
  VideoOptions o = small();
  o.audio_path = (dir_ / "s.wav").string();
  const auto path = write_video("e.mp4", o, 10);
  EXPECT_TRUE(fs::is_regular_file(path));
}

TEST_F(VideoTest, RejectsBadOptionsAndInput) {
  VideoOptions o = small();
  EXPECT_THROW(VideoWriter((dir_ / "x.avi").string(), o), InvalidInput);
  EXPECT_THROW(VideoWriter((dir_ / "x").string(), o), InvalidInput);
  for (auto bad : {0, -3, 20000}) {
    VideoOptions b = small();
    b.width = bad;
    EXPECT_THROW(VideoWriter((dir_ / "x.mp4").string(), b), InvalidInput) << bad;
  }
  for (double fps : {0.0, -1.0, std::nan(""), 1e9}) {
    VideoOptions b = small();
    b.fps = fps;
    EXPECT_THROW(VideoWriter((dir_ / "x.mp4").string(), b), InvalidInput) << fps;
  }
  VideoOptions gif_audio = small();
  gif_audio.audio_path = "whatever.wav";
  EXPECT_THROW(VideoWriter((dir_ / "x.gif").string(), gif_audio), InvalidInput);
  VideoOptions no_audio = small();
  no_audio.audio_path = (dir_ / "missing.wav").string();
  EXPECT_THROW(VideoWriter((dir_ / "x.mp4").string(), no_audio), IoError);
  EXPECT_THROW(VideoWriter((dir_ / "no_such_dir" / "x.mp4").string(), o), IoError);
  {
    VideoWriter w((dir_ / "x.mp4").string(), o);
    EXPECT_THROW(w.add_frame(std::vector<std::uint8_t>(10)), InvalidInput);
    EXPECT_THROW(w.finish(), InvalidInput);  // no frames
  }
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(VideoTest, AbandonedWriterLeavesNothing) {
  {
    VideoWriter w((dir_ / "x.mp4").string(), small());
    w.add_frame(frame(63, 48, 0));
  }
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(VideoTest, MissingBinaryIsAClearError) {
  VideoOptions o = small();
  o.ffmpeg = "emoface-no-such-ffmpeg";
  try {
    VideoWriter w((dir_ / "x.mp4").string(), o);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("emoface-no-such-ffmpeg"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(ffmpeg_available("emoface-no-such-ffmpeg"));
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(VideoTest, FfmpegFailureIsReportedWithItsMessage) {
  std::ofstream(dir_ / "bad.wav") << "this is not audio";
  VideoOptions o = small();
  o.audio_path = (dir_ / "bad.wav").string();
  try {
    VideoWriter w((dir_ / "x.mp4").string(), o);
    for (int k = 0; k < 3; ++k) w.add_frame(frame(63, 48, k));
    w.finish();
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("x.mp4"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.mp4"));
  EXPECT_EQ(file_count(), 1u);  // only bad.wav
}

}  // namespace
}  // namespace emoface::core
