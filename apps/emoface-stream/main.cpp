// emoface-stream: sends a track (face parameters or ARKit weights) at its frame rate over UDP as
// VMC/OSC blend shapes or Live Link Face packets. Thin: parse, read, call faceweights, report.
#include <cmath>
#include <iostream>

#include "emoface/cli/cli.hpp"
#include "emoface/core/version.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/stream.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/muscles/io.hpp"
#include "emoface/muscles/parameters.hpp"

namespace fw = emoface::faceweights;
namespace cli = emoface::cli;

int main(int argc, char** argv) {
  CLI::App app{"Stream a track to an engine over UDP: VMC/OSC blend shapes (/VMC/Ext/Blend/Val + "
               "/VMC/Ext/Blend/Apply) or Live Link Face packets, one per frame at the track's times."};
  std::string track, weights, protocol = "vmc", realtime = "on", names = "livelink";
  fw::StreamOptions o;
  double fps = 0.0;
  int loops = 1;
  bool quiet = false;
  app.add_option("--track", track, "parameter frames (.csv/.ndjson/.json, faceanim's input) or, "
                                   "with --weights arkit, ARKit / Live Link Face CSV")->required();
  app.add_option("--weights", weights, "arkit: the track holds ARKit weights")
      ->check(CLI::IsMember({"arkit"}));
  app.add_option("--protocol", protocol, "vmc|livelink")->check(CLI::IsMember({"vmc", "livelink"}))
      ->capture_default_str();
  app.add_option("--host", o.host, "receiver host name or address")->capture_default_str();
  app.add_option("--port", o.port, "receiver UDP port (VMC 39539, Live Link Face 11111)")
      ->check(CLI::Range(1, 65535))->capture_default_str();
  app.add_option("--realtime", realtime, "on: pace frames by their times; off: send at once (tests)")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  app.add_option("--fps", fps, "frame rate of tracks without times and of Live Link frame numbers "
                               "(0 = from the track, else 60)")->check(CLI::Range(0.0, 1000.0));
  app.add_option("--names", names, "VMC blend shape spelling: raw (eyeBlink_L), swift (eyeBlinkLeft), "
                                   "livelink (EyeBlinkLeft)")
      ->check(CLI::IsMember({"raw", "swift", "livelink"}))->capture_default_str();
  app.add_option("--subject", o.subject, "Live Link subject name")->capture_default_str();
  app.add_option("--loop", loops, "play the track this many times")->check(CLI::Range(1, 1000000));
  app.add_flag("--quiet", quiet, "no summary line");
  app.set_version_flag("--version", emoface::kGenerator);
  app.footer("Example:\n  emoface-stream --track out/obie/tracks.csv --protocol vmc --port 39539\n"
             "  emoface-stream --track capture.csv --weights arkit --protocol livelink --port 11111\n"
             "Exit codes: 0 ok, 1 usage, 2 bad input, 3 numerical, 4 internal.");
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  return cli::run("emoface-stream", [&] {
    o.protocol = protocol == "vmc" ? fw::StreamProtocol::Vmc : fw::StreamProtocol::LiveLinkFace;
    o.realtime = realtime == "on";
    o.names = names == "raw" ? fw::BlendNames::Raw
              : names == "swift" ? fw::BlendNames::Swift : fw::BlendNames::LiveLink;
    std::vector<fw::StreamFrame> frames;
    const double read_fps = fps > 0 ? fps : 60.0;
    if (weights == "arkit") {
      fw::WeightTrackReadOptions r;
      r.fps = read_fps;
      frames = fw::stream_frames_from_track(
          fw::read_weight_track(track, fw::builtin_weight_set("arkit"), r));
    } else {
      emoface::muscles::FrameReadOptions r;
      r.fps = read_fps;
      const auto pf = emoface::muscles::read_parameter_frames(track, r);
      std::vector<double> times;
      std::vector<std::vector<double>> values;
      for (const auto& f : pf) {
        times.push_back(f.time);
        values.push_back(f.values);
      }
      const fw::Mapper arkit(fw::builtin_weight_set("arkit"), emoface::muscles::parameter_names());
      frames = fw::stream_frames_from_parameters(arkit, times, values);
    }
    if (frames.empty()) throw emoface::InvalidInput(track + ": no frames");
    o.fps = fps > 0 ? std::round(fps)
            : frames.size() > 1 && frames[1].time > frames[0].time
                ? std::max(1.0, std::round(1.0 / (frames[1].time - frames[0].time)))
                : 60.0;
    // repeated plays continue the clock: loop k starts one frame after loop k−1 ends
    std::vector<fw::StreamFrame> all;
    const double period = frames.back().time - frames.front().time + 1.0 / o.fps;
    for (int k = 0; k < loops; ++k) {
      for (auto f : frames) {
        f.time += k * period;
        all.push_back(std::move(f));
      }
    }
    const auto report = fw::stream_frames(all, o);
    if (!quiet)
      std::cerr << "emoface-stream: sent " << report.packets << " " << fw::to_string(o.protocol)
                << " packets (" << report.bytes << " bytes) to " << o.host << ":" << o.port << " in "
                << report.seconds << " s\n";
    return 0;
  });
}
