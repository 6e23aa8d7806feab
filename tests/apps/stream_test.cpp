// emoface-stream end to end: a loopback UDP receiver written here gets exactly the packets the
// library encodes for the same track (bounded count, stops by itself; --realtime off, no sleeps).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "cli_harness.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/stream.hpp"
#include "emoface/faceweights/tracks.hpp"

namespace {

class Stream : public emoface::test::CliTest {};

std::vector<std::string> receive(int fd, std::size_t count) {
  std::vector<std::string> out;
  char buf[65536];
  while (out.size() < count) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5000) <= 0) break;
    const auto n = ::recv(fd, buf, sizeof buf, 0);
    if (n < 0) break;
    out.emplace_back(buf, static_cast<std::size_t>(n));
  }
  return out;
}

TEST_F(Stream, SendsArkitTrackAsVmcAndLiveLink) {
  namespace fw = emoface::faceweights;
  // a 3-frame Live Link Face CSV at 30 fps
  std::string csv = "Timecode,BlendShapeCount";
  for (const auto& c : fw::live_link_face_columns()) csv += "," + c;
  csv += "\n";
  for (int f = 0; f < 3; ++f) {
    csv += "00:00:01:0" + std::to_string(f) + ".000,61";
    for (int k = 0; k < 61; ++k) csv += k == 17 ? ",0." + std::to_string(f * 3) : ",0";  // JawOpen
    csv += "\n";
  }
  const std::string track = write("t.csv", csv);
  fw::WeightTrackReadOptions ro;
  ro.fps = 30;
  const auto frames = fw::stream_frames_from_track(
      fw::parse_weight_track(csv, fw::builtin_weight_set("arkit"), "t.csv", ro));

  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  const std::string port = std::to_string(ntohs(a.sin_port));

  for (const std::string protocol : {"vmc", "livelink"}) {
    auto r = run_tool(EMOFACE_STREAM_EXE, "--track " + track + " --weights arkit --fps 30 --protocol " +
                                              protocol + " --port " + port + " --realtime off --loop 2");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("sent 6 " + protocol + " packets"), std::string::npos) << r.err;
    const auto got = receive(fd, 6);
    ASSERT_EQ(got.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& f = frames[i % 3];
      const std::string expected =
          protocol == "vmc" ? fw::vmc_blend_packet(f)
                            : fw::live_link_face_packet(f, "emoface-stream", "emoface",
                                                        static_cast<std::int32_t>(i), 0.0f, 30);
      EXPECT_EQ(got[i], expected) << protocol << " packet " << i;
    }
  }
  ::close(fd);
  EXPECT_EQ(run_tool(EMOFACE_STREAM_EXE, "--track " + track + " --weights arkit --port 0").code, 1);
  EXPECT_EQ(run_tool(EMOFACE_STREAM_EXE, "--track " + path("missing.csv") + " --port 9").code, 2);
}

}  // namespace
