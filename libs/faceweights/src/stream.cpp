#include "emoface/faceweights/stream.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/tracks.hpp"

namespace emoface::faceweights {

namespace osc {

void append_string(std::string& out, std::string_view s) {
  out.append(s.data(), s.size());
  out.push_back('\0');
  while (out.size() % 4) out.push_back('\0');
}

void append_int32(std::string& out, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((u >> shift) & 0xFF));
}

void append_float32(std::string& out, float v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  append_int32(out, static_cast<std::int32_t>(u));
}

std::string message(std::string_view address, std::string_view tags,
                    const std::vector<std::string>& strings, const std::vector<float>& floats) {
  if (address.empty() || address[0] != '/') throw InvalidInput("osc: address must start with '/'");
  std::size_t ns = 0, nf = 0;
  for (char t : tags) {
    if (t == 's') ++ns;
    else if (t == 'f') ++nf;
    else throw InvalidInput("osc: only 's' and 'f' arguments are supported");
  }
  if (ns != strings.size() || nf != floats.size()) throw InvalidInput("osc: tags do not match the values");
  std::string out;
  append_string(out, address);
  append_string(out, "," + std::string(tags));
  std::size_t is = 0, jf = 0;
  for (char t : tags) {
    if (t == 's') append_string(out, strings[is++]);
    else append_float32(out, floats[jf++]);
  }
  return out;
}

std::string bundle(const std::vector<std::string>& elements, std::uint64_t time_tag) {
  std::string out;
  append_string(out, "#bundle");
  append_int32(out, static_cast<std::int32_t>(time_tag >> 32));
  append_int32(out, static_cast<std::int32_t>(time_tag & 0xFFFFFFFFu));
  for (const auto& e : elements) {
    append_int32(out, static_cast<std::int32_t>(e.size()));
    out += e;
  }
  return out;
}

}  // namespace osc

namespace {

void check_frame(const StreamFrame& f) {
  if (f.weights.size() != arkit_names().size())
    throw InvalidInput("stream: a frame needs " + std::to_string(arkit_names().size()) + " ARKit weights");
  for (double w : f.weights) {
    if (!std::isfinite(w)) throw InvalidInput("stream: weight not finite");
  }
  for (const auto& [k, v] : f.angles) {
    if (!std::isfinite(v)) throw InvalidInput("stream: angle '" + k + "' not finite");
  }
}

double angle(const StreamFrame& f, const char* name) {
  auto it = f.angles.find(name);
  return it == f.angles.end() ? 0.0 : it->second;
}

}  // namespace

std::string vmc_blend_packet(const StreamFrame& frame, BlendNames names) {
  check_frame(frame);
  std::vector<std::string> elements;
  const auto& raw = arkit_names();
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::string name = names == BlendNames::Raw     ? raw[i]
                             : names == BlendNames::Swift ? arkit_swift_name(raw[i])
                                                          : live_link_face_name(raw[i]);
    elements.push_back(osc::message("/VMC/Ext/Blend/Val", "sf", {name}, {static_cast<float>(frame.weights[i])}));
  }
  elements.push_back(osc::message("/VMC/Ext/Blend/Apply", "", {}, {}));
  return osc::bundle(elements, 1);
}

std::string live_link_face_packet(const StreamFrame& frame, std::string_view device_id,
                                  std::string_view subject, std::int32_t frame_number,
                                  float sub_frame, std::int32_t fps, std::int32_t denominator) {
  check_frame(frame);
  std::string out;
  out.push_back(static_cast<char>(6));  // packet version
  osc::append_int32(out, static_cast<std::int32_t>(device_id.size()));
  out.append(device_id.data(), device_id.size());
  osc::append_int32(out, static_cast<std::int32_t>(subject.size()));
  out.append(subject.data(), subject.size());
  osc::append_int32(out, frame_number);
  osc::append_float32(out, sub_frame);
  osc::append_int32(out, fps);
  osc::append_int32(out, denominator);
  out.push_back(static_cast<char>(61));
  for (int k : live_link_face_to_arkit()) osc::append_float32(out, static_cast<float>(frame.weights[static_cast<std::size_t>(k)]));
  const double values[9] = {angle(frame, "head_yaw"),     angle(frame, "head_pitch"),
                            angle(frame, "head_roll"),    angle(frame, "eye_gaze_yaw"),
                            angle(frame, "eye_gaze_pitch"), 0.0,
                            angle(frame, "eye_gaze_yaw"), angle(frame, "eye_gaze_pitch"), 0.0};
  for (double v : values) osc::append_float32(out, static_cast<float>(v));
  return out;
}

std::vector<StreamFrame> stream_frames_from_track(const WeightTrack& track) {
  if (track.targets != arkit_names())
    throw InvalidInput("stream: the track must hold the 52 ARKit shapes (the arkit weight set)");
  std::vector<StreamFrame> out(track.weights.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].time = track.times[i];
    out[i].weights = track.weights[i];
    if (i < track.pose.size()) out[i].angles = track.pose[i];
  }
  return out;
}

std::vector<StreamFrame> stream_frames_from_parameters(const Mapper& arkit,
                                                       const std::vector<double>& times,
                                                       const std::vector<std::vector<double>>& frames) {
  if (arkit.set().target_names() != arkit_names())
    throw InvalidInput("stream: the mapper must use the arkit weight set");
  if (times.size() != frames.size()) throw InvalidInput("stream: one time per frame");
  const auto& names = arkit.parameter_names();
  std::vector<StreamFrame> out(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    out[i].time = times[i];
    out[i].weights = arkit.forward(frames[i]);
    for (const char* a : {"head_yaw", "head_pitch", "head_roll", "eye_gaze_yaw", "eye_gaze_pitch"}) {
      for (std::size_t k = 0; k < names.size(); ++k) {
        if (names[k] == a) out[i].angles[a] = frames[i][k];
      }
    }
  }
  return out;
}

std::string_view to_string(StreamProtocol p) noexcept {
  return p == StreamProtocol::Vmc ? "vmc" : "livelink";
}

void StreamOptions::validate() const {
  if (port < 1 || port > 65535) throw InvalidInput("stream: port must be in 1..65535");
  if (host.empty()) throw InvalidInput("stream: empty host");
  if (!(fps > 0.0) || fps > 1000.0 || std::fabs(fps - std::round(fps)) > 1e-9)
    throw InvalidInput("stream: fps must be an integer in 1..1000");
  if (subject.size() > 255 || device_id.size() > 255)
    throw InvalidInput("stream: subject and device id are at most 255 bytes");
}

UdpSender::UdpSender(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* res = nullptr;
  const int rc = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res);
  if (rc != 0 || !res) throw IoError("stream: cannot resolve '" + host + "': " + ::gai_strerror(rc));
  fd_ = ::socket(res->ai_family, res->ai_socktype, res->ai_protocol);
  if (fd_ < 0) {
    ::freeaddrinfo(res);
    throw IoError("stream: cannot open a UDP socket: " + std::string(std::strerror(errno)));
  }
  address_.assign(reinterpret_cast<unsigned char*>(res->ai_addr),
                  reinterpret_cast<unsigned char*>(res->ai_addr) + res->ai_addrlen);
  ::freeaddrinfo(res);
}

UdpSender::~UdpSender() {
  if (fd_ >= 0) ::close(fd_);
}

void UdpSender::send(std::string_view datagram) {
  const auto n = ::sendto(fd_, datagram.data(), datagram.size(), 0,
                          reinterpret_cast<const sockaddr*>(address_.data()),
                          static_cast<socklen_t>(address_.size()));
  if (n < 0 || static_cast<std::size_t>(n) != datagram.size())
    throw IoError("stream: sendto failed: " + std::string(std::strerror(errno)));
}

StreamReport stream_frames(const std::vector<StreamFrame>& frames, const StreamOptions& options,
                           const std::function<void(std::string_view)>& send) {
  options.validate();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    check_frame(frames[i]);
    if (!std::isfinite(frames[i].time) || (i > 0 && frames[i].time < frames[i - 1].time))
      throw InvalidInput("stream: frame times must be finite and non-decreasing");
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double t0 = frames.empty() ? 0.0 : frames.front().time;
  const auto fps = static_cast<std::int32_t>(std::lround(options.fps));
  StreamReport report;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const StreamFrame& f = frames[i];
    if (options.realtime)
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(f.time - t0)));
    std::string packet;
    if (options.protocol == StreamProtocol::Vmc) {
      packet = vmc_blend_packet(f, options.names);
    } else {
      // snapped to a millionth of a frame so k/fps seconds is frame k with sub-frame 0
      const double frames_since = std::round((f.time - t0) * fps * 1e6) / 1e6;
      const auto whole = static_cast<std::int32_t>(std::floor(frames_since));
      packet = live_link_face_packet(f, options.device_id, options.subject, whole,
                                     static_cast<float>(frames_since - whole), fps, 1);
    }
    send(packet);
    ++report.packets;
    report.bytes += packet.size();
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

StreamReport stream_frames(const std::vector<StreamFrame>& frames, const StreamOptions& options) {
  options.validate();
  UdpSender sender(options.host, options.port);
  return stream_frames(frames, options, [&](std::string_view d) { sender.send(d); });
}

}  // namespace emoface::faceweights
