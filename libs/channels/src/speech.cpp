#include "emoface/channels/speech.hpp"

#include <espeak-ng/speak_lib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"

namespace emoface::channels {

namespace {

std::mutex& espeak_mutex() {
  static std::mutex m;
  return m;
}

struct Capture {
  std::vector<std::int16_t> samples;
  std::vector<std::pair<std::string, int>> phonemes;  // mnemonic, start in ms
  int end_ms = -1;
};
Capture* g_capture = nullptr;  // guarded by espeak_mutex()

int on_synth(short* wav, int n, espeak_EVENT* ev) {
  if (!g_capture) return 1;
  if (wav && n > 0) g_capture->samples.insert(g_capture->samples.end(), wav, wav + n);
  for (; ev && ev->type != espeakEVENT_LIST_TERMINATED; ++ev) {
    if (ev->type == espeakEVENT_PHONEME) {
      char buf[9] = {0};
      std::memcpy(buf, ev->id.string, 8);
      g_capture->phonemes.emplace_back(buf, ev->audio_position);
    } else if (ev->type == espeakEVENT_END || ev->type == espeakEVENT_MSG_TERMINATED) {
      g_capture->end_ms = std::max(g_capture->end_ms, ev->audio_position);
    }
  }
  return 0;
}

int initialise() {
  static int rate = [] {
    const int r = espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr,
                                    espeakINITIALIZE_PHONEME_EVENTS | espeakINITIALIZE_DONT_EXIT);
    if (r > 0) espeak_SetSynthCallback(on_synth);
    return r;
  }();
  if (rate <= 0) throw Error("espeak-ng could not be initialised (is espeak-ng-data installed?)");
  return rate;
}

}  // namespace

void SpeechOptions::validate() const {
  if (voice.empty() || voice.size() > 64) throw InvalidInput("speech: bad voice name");
  if (rate < 80 || rate > 450) throw InvalidInput("speech: rate must be in [80, 450] words/min");
  if (pitch < 0 || pitch > 99) throw InvalidInput("speech: pitch must be in [0, 99]");
}

Utterance synthesize(std::string_view text, const SpeechOptions& options) {
  options.validate();
  if (std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); }))
    throw InvalidInput("speech: empty text");
  if (!core::is_valid_utf8(text)) throw InvalidInput("speech: text is not valid UTF-8");
  if (text.find('\0') != std::string_view::npos) throw InvalidInput("speech: text contains NUL");
  std::lock_guard<std::mutex> lock(espeak_mutex());
  const int sample_rate = initialise();
  if (espeak_SetVoiceByName(options.voice.c_str()) != EE_OK)
    throw InvalidInput("speech: espeak-ng has no voice '" + options.voice + "'");
  espeak_SetParameter(espeakRATE, options.rate, 0);
  espeak_SetParameter(espeakPITCH, options.pitch, 0);
  Capture cap;
  g_capture = &cap;
  const std::string buf(text);
  const auto err = espeak_Synth(buf.c_str(), buf.size() + 1, 0, POS_CHARACTER, 0, espeakCHARS_UTF8, nullptr, nullptr);
  espeak_Synchronize();
  g_capture = nullptr;
  if (err != EE_OK) throw Error("speech: espeak-ng synthesis failed");
  Utterance u;
  u.sample_rate = sample_rate;
  u.samples = std::move(cap.samples);
  const double total = u.duration();
  // phoneme k spans [start_k, start_{k+1}); the last one ends with the audio (espeak-ng events are
  // in ms of audio position, so the lip track and the WAV share one clock)
  for (std::size_t k = 0; k < cap.phonemes.size(); ++k) {
    const double s = std::min(cap.phonemes[k].second / 1000.0, total);
    const double e = k + 1 < cap.phonemes.size() ? std::min(cap.phonemes[k + 1].second / 1000.0, total) : total;
    if (e > s) u.phonemes.push_back({cap.phonemes[k].first, s, e});
  }
  return u;
}

std::vector<std::int16_t> place_utterances(const std::vector<Utterance>& utterances,
                                           const std::vector<double>& start_times, int sample_rate,
                                           double min_duration) {
  if (utterances.size() != start_times.size()) throw InvalidInput("place_utterances: size mismatch");
  if (sample_rate <= 0) throw InvalidInput("place_utterances: bad sample rate");
  std::size_t total = static_cast<std::size_t>(std::ceil(std::max(0.0, min_duration) * sample_rate));
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (std::size_t i = 0; i < utterances.size(); ++i) {
    if (utterances[i].sample_rate != sample_rate) throw InvalidInput("place_utterances: sample rates differ");
    if (!(start_times[i] >= 0 && std::isfinite(start_times[i]))) throw InvalidInput("place_utterances: bad start time");
    const auto first = static_cast<std::size_t>(std::llround(start_times[i] * sample_rate));
    spans.emplace_back(first, first + utterances[i].samples.size());
    total = std::max(total, spans.back().second);
  }
  std::vector<std::int16_t> out(total, 0);
  for (std::size_t i = 0; i < utterances.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (spans[i].first < spans[j].second && spans[j].first < spans[i].second)
        throw InvalidInput("place_utterances: utterances overlap");
    std::copy(utterances[i].samples.begin(), utterances[i].samples.end(), out.begin() + static_cast<std::ptrdiff_t>(spans[i].first));
  }
  return out;
}

std::string format_wav(const std::vector<std::int16_t>& samples, int sample_rate) {
  if (sample_rate <= 0) throw InvalidInput("wav: bad sample rate");
  // RIFF INFO list after the samples (readers that only know "fmt " and "data" skip it): ISFT = software.
  std::string software(kGenerator);
  software.push_back('\0');
  if (software.size() % 2) software.push_back('\0');  // chunks are word-aligned
  const std::uint64_t list_bytes = 4 + 8 + software.size();  // "INFO" + ISFT header + text
  const std::uint64_t data_bytes = samples.size() * 2;
  if (data_bytes > 0xFFFFFFF0u - 36 - 8 - list_bytes) throw InvalidInput("wav: too long");
  std::string out;
  const auto u32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF); };
  const auto u16 = [&](std::uint16_t v) { out += static_cast<char>(v & 0xFF); out += static_cast<char>(v >> 8); };
  out += "RIFF";
  u32(static_cast<std::uint32_t>(36 + data_bytes + 8 + list_bytes));
  out += "WAVEfmt ";
  u32(16);
  u16(1);  // PCM
  u16(1);  // mono
  u32(static_cast<std::uint32_t>(sample_rate));
  u32(static_cast<std::uint32_t>(sample_rate * 2));
  u16(2);
  u16(16);
  out += "data";
  u32(static_cast<std::uint32_t>(data_bytes));
  for (std::int16_t s : samples) u16(static_cast<std::uint16_t>(s));
  out += "LIST";
  u32(static_cast<std::uint32_t>(list_bytes));
  out += "INFOISFT";
  u32(static_cast<std::uint32_t>(software.size()));
  out += software;
  return out;
}

void write_wav(const std::string& path, const std::vector<std::int16_t>& samples, int sample_rate) {
  core::write_file_atomic(path, format_wav(samples, sample_rate));
}

}  // namespace emoface::channels
