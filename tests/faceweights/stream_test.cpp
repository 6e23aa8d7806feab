#include "emoface/faceweights/stream.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::faceweights {
namespace {

std::string bytes(std::initializer_list<int> b) {
  std::string s;
  for (int x : b) s.push_back(static_cast<char>(x));
  return s;
}

// OSC 1.0 by hand: strings NUL-terminated and padded to 4, float32 big-endian (1.0f = 3F800000,
// 0.5f = 3F000000), bundle = "#bundle\0" + 8-byte time tag + (int32 size, element)*.
TEST(Osc, MessagesByteForByte) {
  std::string s;
  osc::append_string(s, "abc");
  EXPECT_EQ(s, bytes({'a', 'b', 'c', 0}));
  s.clear();
  osc::append_string(s, "abcd");
  EXPECT_EQ(s, bytes({'a', 'b', 'c', 'd', 0, 0, 0, 0}));
  s.clear();
  osc::append_string(s, "");
  EXPECT_EQ(s, bytes({0, 0, 0, 0}));
  s.clear();
  osc::append_float32(s, -2.5f);  // C0200000
  EXPECT_EQ(s, bytes({0xC0, 0x20, 0, 0}));
  s.clear();
  osc::append_int32(s, 0x01020304);
  EXPECT_EQ(s, bytes({1, 2, 3, 4}));

  const std::string val = osc::message("/VMC/Ext/Blend/Val", "sf", {"A"}, {1.0f});
  const std::string expected_val = std::string("/VMC/Ext/Blend/Val") + bytes({0, 0}) +  // 18 + 2
                                   bytes({',', 's', 'f', 0}) + bytes({'A', 0, 0, 0}) +
                                   bytes({0x3F, 0x80, 0, 0});
  EXPECT_EQ(val, expected_val);
  EXPECT_EQ(val.size(), 32u);
  const std::string apply = osc::message("/VMC/Ext/Blend/Apply", "", {}, {});
  EXPECT_EQ(apply, std::string("/VMC/Ext/Blend/Apply") + bytes({0, 0, 0, 0}) + bytes({',', 0, 0, 0}));
  const std::string b = osc::bundle({apply}, 1);
  EXPECT_EQ(b, std::string("#bundle") + bytes({0}) + bytes({0, 0, 0, 0, 0, 0, 0, 1}) +
                   bytes({0, 0, 0, 28}) + apply);
  EXPECT_THROW(osc::message("VMC", "", {}, {}), InvalidInput);
  EXPECT_THROW(osc::message("/a", "sf", {"x"}, {}), InvalidInput);
  EXPECT_THROW(osc::message("/a", "i", {}, {}), InvalidInput);
}

StreamFrame frame_with(const std::string& shape, double w) {
  StreamFrame f;
  f.weights.assign(52, 0.0);
  const auto& n = arkit_names();
  f.weights[static_cast<std::size_t>(std::find(n.begin(), n.end(), shape) - n.begin())] = w;
  return f;
}

TEST(Vmc, BundleOfFiftyTwoValuesAndApply) {
  const auto p = vmc_blend_packet(frame_with("jawOpen", 0.5), BlendNames::LiveLink);
  // the JawOpen message, by hand
  const std::string jaw = std::string("/VMC/Ext/Blend/Val") + bytes({0, 0}) + bytes({',', 's', 'f', 0}) +
                          std::string("JawOpen") + bytes({0}) + bytes({0x3F, 0, 0, 0});
  EXPECT_NE(p.find(bytes({0, 0, 0, 36}) + jaw), std::string::npos);
  EXPECT_EQ(p.rfind(std::string("/VMC/Ext/Blend/Apply")), p.size() - 28);
  EXPECT_EQ(p.substr(0, 16), std::string("#bundle") + bytes({0, 0, 0, 0, 0, 0, 0, 0, 1}));
  // 53 elements: count the size prefixes by walking the bundle
  std::size_t pos = 16, count = 0;
  while (pos < p.size()) {
    const auto size = (static_cast<unsigned char>(p[pos]) << 24) | (static_cast<unsigned char>(p[pos + 1]) << 16) |
                      (static_cast<unsigned char>(p[pos + 2]) << 8) | static_cast<unsigned char>(p[pos + 3]);
    pos += 4 + static_cast<std::size_t>(size);
    ++count;
  }
  EXPECT_EQ(pos, p.size());
  EXPECT_EQ(count, 53u);
  EXPECT_NE(vmc_blend_packet(frame_with("jawOpen", 0.5), BlendNames::Raw).find("jawOpen"), std::string::npos);
  EXPECT_NE(vmc_blend_packet(frame_with("eyeBlink_L", 1), BlendNames::Swift).find("eyeBlinkLeft"),
            std::string::npos);
}

TEST(LiveLinkFace, PacketByteForByte) {
  StreamFrame f = frame_with("eyeBlink_L", 1.0);  // EyeBlinkLeft is value 0 in Live Link order
  f.angles["head_yaw"] = 0.5;                      // HeadYaw is value 52
  const auto p = live_link_face_packet(f, "d", "s", 2, 0.5f, 60, 1);
  std::string expected = bytes({6}) + bytes({0, 0, 0, 1}) + "d" + bytes({0, 0, 0, 1}) + "s" +
                         bytes({0, 0, 0, 2}) + bytes({0x3F, 0, 0, 0}) + bytes({0, 0, 0, 60}) +
                         bytes({0, 0, 0, 1}) + bytes({61}) + bytes({0x3F, 0x80, 0, 0});
  for (int i = 1; i < 61; ++i) expected += i == 52 ? bytes({0x3F, 0, 0, 0}) : bytes({0, 0, 0, 0});
  EXPECT_EQ(p, expected);
  EXPECT_EQ(p.size(), 1u + 5 + 5 + 16 + 1 + 61 * 4);
  StreamFrame bad = f;
  bad.weights.pop_back();
  EXPECT_THROW(live_link_face_packet(bad, "d", "s", 0, 0, 60), InvalidInput);
}

// A loopback receiver: binds 127.0.0.1 on a free port, receives at most `count` datagrams, waiting
// at most 2 s for each, then stops by itself.
class Receiver {
 public:
  Receiver() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~Receiver() { ::close(fd_); }
  int port() const { return port_; }
  std::vector<std::string> receive(std::size_t count) {
    std::vector<std::string> out;
    char buf[65536];
    while (out.size() < count) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 2000) <= 0) break;
      const auto n = ::recv(fd_, buf, sizeof buf, 0);
      if (n < 0) break;
      out.emplace_back(buf, static_cast<std::size_t>(n));
    }
    return out;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

std::vector<StreamFrame> three_frames() {
  std::vector<StreamFrame> f = {frame_with("jawOpen", 0.0), frame_with("jawOpen", 0.5),
                                frame_with("mouthSmile_R", 1.0)};
  for (std::size_t i = 0; i < f.size(); ++i) f[i].time = static_cast<double>(i) / 50.0;
  return f;
}

TEST(Stream, VmcOverLoopbackUdp) {
  Receiver rx;
  StreamOptions o;
  o.protocol = StreamProtocol::Vmc;
  o.port = rx.port();
  o.realtime = false;
  const auto frames = three_frames();
  const auto report = stream_frames(frames, o);
  EXPECT_EQ(report.packets, 3u);
  const auto got = rx.receive(3);
  ASSERT_EQ(got.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(got[i], vmc_blend_packet(frames[i], o.names));
}

TEST(Stream, LiveLinkFaceOverLoopbackUdpWithFrameNumbers) {
  Receiver rx;
  StreamOptions o;
  o.protocol = StreamProtocol::LiveLinkFace;
  o.port = rx.port();
  o.realtime = true;  // 3 frames at 50 fps: 40 ms
  o.fps = 50;
  const auto frames = three_frames();
  const auto report = stream_frames(frames, o);
  EXPECT_GE(report.seconds, 0.039);
  const auto got = rx.receive(3);
  ASSERT_EQ(got.size(), 3u);
  for (std::int32_t i = 0; i < 3; ++i)
    EXPECT_EQ(got[static_cast<std::size_t>(i)],
              live_link_face_packet(frames[static_cast<std::size_t>(i)], o.device_id, o.subject, i, 0.0f, 50));
}

TEST(Stream, FramesFromParametersAndTracks) {
  const auto& names = muscles::parameter_names();
  const Mapper arkit(builtin_weight_set("arkit"), names);
  std::vector<double> p(names.size(), 0.0);
  p[muscles::parameter_index("masseter")] = 0.7;
  p[muscles::parameter_index("head_pitch")] = -0.2;
  const auto frames = stream_frames_from_parameters(arkit, {0.0}, {p});
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_NEAR(frames[0].weights[24], 0.7, 1e-12);  // jawOpen
  EXPECT_NEAR(frames[0].angles.at("head_pitch"), -0.2, 1e-12);
  const auto text = format_weight_track(TrackFormat::ArkitCsv, names, {0.0}, {p}, 25);
  const auto back = stream_frames_from_track(parse_weight_track(text, builtin_weight_set("arkit"), "t"));
  EXPECT_NEAR(back[0].weights[24], 0.7, 1e-6);
}

TEST(Stream, BadOptionsAndFrames) {
  StreamOptions o;
  o.port = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o.port = 9;
  o.fps = 29.97;
  EXPECT_THROW(o.validate(), InvalidInput);
  o.fps = 30;
  auto frames = three_frames();
  frames[2].time = 0.0;  // goes back in time
  EXPECT_THROW(stream_frames(frames, o, [](std::string_view) {}), InvalidInput);
  frames = three_frames();
  frames[1].weights[0] = std::nan("");
  EXPECT_THROW(stream_frames(frames, o, [](std::string_view) {}), InvalidInput);
  o.host = "no-such-host.invalid";
  EXPECT_THROW(stream_frames(three_frames(), o), IoError);
}

}  // namespace
}  // namespace emoface::faceweights
