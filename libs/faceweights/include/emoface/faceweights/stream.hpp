#pragma once
// Streaming weight tracks to engines over UDP:
//
//   VMC/OSC   one OSC 1.0 bundle per frame (time tag 1 = "immediately") holding one
//             "/VMC/Ext/Blend/Val" message (s name, f value) per ARKit shape and one
//             "/VMC/Ext/Blend/Apply" (no arguments) — the blend-shape part of the VMC protocol
//             (protocol.vmc.info); OSC 1.0 encoding (opensoundcontrol.org, spec 1.0) written here:
//             strings NUL-terminated and padded to 4 bytes, int32 / float32 big-endian, bundles
//             "#bundle", 8-byte NTP time tag, then (int32 size, element) pairs.
//   Live Link Face   Epic's Live Link Face app's version-6 ARKit packet, as decoded by public
//             receivers (the PyLiveLinkFace decoder and its ports; no official specification was
//             found): uint8 version = 6; int32 BE length + device id (UTF-8); int32 BE length +
//             subject name; int32 BE frame number; float32 BE sub-frame; int32 BE frame rate
//             numerator; int32 BE denominator; uint8 value count = 61; 61 float32 BE values in
//             live_link_face_columns() order (52 shapes, then head and eye angles).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::faceweights {

namespace osc {
void append_string(std::string& out, std::string_view s);  ///< OSC-string: NUL + pad to 4
void append_int32(std::string& out, std::int32_t v);       ///< big-endian
void append_float32(std::string& out, float v);            ///< IEEE 754, big-endian
/// One OSC message whose arguments are all strings or floats, given as type tags ("sf", "" …)
/// and values in order. Throws InvalidInput if the tags do not match the values.
std::string message(std::string_view address, std::string_view tags,
                    const std::vector<std::string>& strings, const std::vector<float>& floats);
/// A bundle of encoded elements with a 64-bit NTP time tag (1 = immediately).
std::string bundle(const std::vector<std::string>& elements, std::uint64_t time_tag = 1);
}  // namespace osc

/// One frame to stream: the 52 ARKit weights (arkit_names() order, [0, 1]) and the head and eye
/// angles (radians, emoface conventions: head_yaw, head_pitch, head_roll, eye_gaze_yaw,
/// eye_gaze_pitch; missing = 0).
struct StreamFrame {
  double time = 0.0;
  std::vector<double> weights;
  std::map<std::string, double> angles;
};

struct WeightTrack;
class Mapper;
/// Frames of an ARKit weight track (its angles copied).
std::vector<StreamFrame> stream_frames_from_track(const WeightTrack& track);
/// Frames from parameter frames (`frames[i]` in `arkit.parameter_names()` order) through an ARKit
/// mapper; the head and gaze angles are copied where the parameter list has them.
std::vector<StreamFrame> stream_frames_from_parameters(const Mapper& arkit,
                                                       const std::vector<double>& times,
                                                       const std::vector<std::vector<double>>& frames);

enum class BlendNames { Raw, Swift, LiveLink };  ///< eyeBlink_L, eyeBlinkLeft, EyeBlinkLeft

/// The VMC bundle of one frame (names in the chosen spelling).
std::string vmc_blend_packet(const StreamFrame& frame, BlendNames names = BlendNames::LiveLink);

/// The Live Link Face packet of one frame.
std::string live_link_face_packet(const StreamFrame& frame, std::string_view device_id,
                                  std::string_view subject, std::int32_t frame_number,
                                  float sub_frame, std::int32_t fps, std::int32_t denominator = 1);

enum class StreamProtocol { Vmc, LiveLinkFace };
std::string_view to_string(StreamProtocol p) noexcept;  ///< "vmc", "livelink"

struct StreamOptions {
  StreamProtocol protocol = StreamProtocol::Vmc;
  std::string host = "127.0.0.1";  ///< name or address (IPv4 or IPv6)
  int port = 39539;                ///< 1–65535 (VMC's default performer port 39539; Live Link 11111)
  bool realtime = true;            ///< send frame i at start + time_i; false: as fast as possible
  double fps = 60.0;               ///< Live Link Face frame rate (integer) and frame numbers
  BlendNames names = BlendNames::LiveLink;
  std::string subject = "emoface";
  std::string device_id = "emoface-stream";
  void validate() const;  ///< throws InvalidInput
};

struct StreamReport {
  std::size_t packets = 0;
  std::size_t bytes = 0;
  double seconds = 0.0;  ///< wall time spent
};

/// Sends UDP datagrams to host:port (resolved once). Throws IoError on failure.
class UdpSender {
 public:
  UdpSender(const std::string& host, int port);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;
  void send(std::string_view datagram);

 private:
  int fd_ = -1;
  std::vector<unsigned char> address_;  // sockaddr storage
};

/// Encodes every frame with the chosen protocol and hands each datagram to `send`, paced by the
/// frame times when options.realtime. Frames must have 52 weights and non-decreasing times.
StreamReport stream_frames(const std::vector<StreamFrame>& frames, const StreamOptions& options,
                           const std::function<void(std::string_view)>& send);
/// The same over UDP to options.host:options.port.
StreamReport stream_frames(const std::vector<StreamFrame>& frames, const StreamOptions& options);

}  // namespace emoface::faceweights
