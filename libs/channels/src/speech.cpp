#include "emoface/channels/speech.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/process.hpp"
#include "emoface/core/version.hpp"

namespace emoface::channels {

namespace {

void check_text(std::string_view text) {
  if (std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); }))
    throw InvalidInput("speech: empty text");
  if (!core::is_valid_utf8(text)) throw InvalidInput("speech: text is not valid UTF-8");
  if (text.find('\0') != std::string_view::npos) throw InvalidInput("speech: text contains NUL");
}

bool is_pause(std::string_view p) { return !p.empty() && p[0] == '_'; }

bool is_stop(std::string_view p) {
  static const char* const stops[] = {"p",  "b",  "t",  "d",  "k",  "g",
                                      "tS", "dZ", "t#", "d#", "t2", "d2"};
  for (const char* s : stops)
    if (p == s) return true;
  return false;
}

bool is_vowel_char(char c) { return std::strchr("aeiouAEIOUVY03@", c) != nullptr && c != '\0'; }

// Nominal duration (ms) of an espeak-ng mnemonic: only the proportions matter, inside a stretch
// between anchors. Class means of libespeak-ng 1.51's phoneme events (en-us, 160 words/min) over
// 24 English sentences, measured once when the library was dropped (docs/channels.md).
double nominal_ms(std::string_view p) {
  if (is_pause(p)) return p == "_" ? 10.0 : 60.0;
  if (is_stop(p)) return p == "tS" || p == "dZ" ? 70.0 : 60.0;
  if (!p.empty() && is_vowel_char(p[0])) {
    std::size_t vowels = 0;
    for (char c : p) vowels += is_vowel_char(c) ? 1 : 0;
    const bool long_vowel = p.find(':') != std::string_view::npos || vowels >= 2;
    return long_vowel ? 160.0 : 100.0;
  }
  return 85.0;
}

constexpr double kFinalLengthening = 1.8;

// Start times of tokens laid out between anchors (token index → time; anchors sorted by index
// and time, the first at token 0, the last at token n = the end).
std::vector<double> layout(const std::vector<std::pair<std::size_t, double>>& anchors,
                           const std::vector<double>& weight) {
  std::vector<double> start(weight.size() + 1, 0.0);
  for (std::size_t a = 0; a + 1 < anchors.size(); ++a) {
    const auto [i0, t0] = anchors[a];
    const auto [i1, t1] = anchors[a + 1];
    double total = 0.0;
    for (std::size_t i = i0; i < i1; ++i) total += weight[i];
    double acc = 0.0;
    for (std::size_t i = i0; i <= i1; ++i) {
      start[i] = total > 0 ? t0 + (t1 - t0) * acc / total : t0;
      if (i < i1) acc += weight[i];
    }
  }
  return start;
}

void insert_anchor(std::vector<std::pair<std::size_t, double>>& anchors, std::size_t index,
                   double t) {
  auto it = std::lower_bound(anchors.begin(), anchors.end(), std::make_pair(index, -1e300));
  if (it != anchors.end() && it->first == index) {
    it->second = t;
  } else {
    anchors.insert(it, {index, t});
  }
}

}  // namespace

void SpeechOptions::validate() const {
  if (voice.empty() || voice.size() > 64) throw InvalidInput("speech: bad voice name");
  for (char c : voice)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '+' ||
          c == '/'))
      throw InvalidInput("speech: bad character in voice name '" + voice + "'");
  if (rate < 80 || rate > 450) throw InvalidInput("speech: rate must be in [80, 450] words/min");
  if (pitch < 0 || pitch > 99) throw InvalidInput("speech: pitch must be in [0, 99]");
  if (program.empty()) throw InvalidInput("speech: empty program name");
}

void AlignOptions::validate() const {
  if (silence_level < 0 || silence_level > 32767)
    throw InvalidInput("align: silence_level must be in [0, 32767]");
  if (!(min_silence > 0 && min_silence <= 1))
    throw InvalidInput("align: min_silence must be in (0, 1] s");
  if (!(stop_tolerance > 0 && std::isfinite(stop_tolerance)))
    throw InvalidInput("align: stop_tolerance must be > 0");
}

std::vector<std::vector<std::string>> parse_espeak_phonemes(std::string_view text) {
  std::vector<std::vector<std::string>> clauses;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    std::vector<std::string> clause;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      std::string_view tok = line.substr(i, j - i);
      while (!tok.empty() && (tok[0] == '\'' || tok[0] == ',' || tok[0] == '%' || tok[0] == '='))
        tok.remove_prefix(1);
      if (!tok.empty()) clause.emplace_back(tok);
      i = j;
    }
    if (!clause.empty()) clauses.push_back(std::move(clause));
  }
  return clauses;
}

std::vector<PhonemeTiming> align_phonemes(const std::vector<std::vector<std::string>>& clauses,
                                          const std::vector<std::int16_t>& samples, int sample_rate,
                                          const AlignOptions& options) {
  options.validate();
  if (sample_rate <= 0) throw InvalidInput("align: bad sample rate");
  std::vector<std::string> tok;
  for (const auto& c : clauses) {
    if (c.empty()) continue;
    tok.insert(tok.end(), c.begin(), c.end());
    tok.emplace_back("_:");  // the clause pause (libespeak-ng reports one after every clause)
  }
  std::vector<PhonemeTiming> out;
  const double total = static_cast<double>(samples.size()) / sample_rate;
  if (tok.empty() || samples.empty()) return out;
  const std::size_t n = tok.size();
  std::vector<double> weight(n);
  for (std::size_t i = 0; i < n; ++i) weight[i] = nominal_ms(tok[i]);
  // clause-final lengthening: the last vowel of a clause lasts about twice as long (same
  // calibration)
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_pause(tok[i]) || i == 0 || is_pause(tok[i - 1])) continue;
    for (std::size_t k = i; k-- > 0 && !is_pause(tok[k]);) {
      if (is_vowel_char(tok[k][0])) {
        weight[k] *= kFinalLengthening;
        break;
      }
    }
  }

  // runs of digital silence [s, e), seconds
  struct Run {
    double s, e;
  };
  std::vector<Run> runs;
  const auto min_len = static_cast<std::size_t>(std::ceil(options.min_silence * sample_rate));
  for (std::size_t i = 0; i < samples.size();) {
    if (std::abs(static_cast<int>(samples[i])) > options.silence_level) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < samples.size() && std::abs(static_cast<int>(samples[j])) <= options.silence_level)
      ++j;
    if (j - i >= min_len || j == samples.size())
      runs.push_back({static_cast<double>(i) / sample_rate, static_cast<double>(j) / sample_rate});
    i = j;
  }
  std::vector<std::pair<std::size_t, double>> anchors{{0, 0.0}, {n, total}};
  std::vector<char> used(runs.size(), 0);
  // the final clause pause takes trailing silence
  if (!runs.empty() && runs.back().e >= total && runs.back().s > 0) {
    insert_anchor(anchors, n - 1, runs.back().s);
    used.back() = 1;
  } else {
    insert_anchor(anchors, n - 1, total);  // no trailing silence: the final pause has no time
  }
  if (!runs.empty() && runs.front().s <= 0)
    used.front() = 1;  // leading silence: part of the first phoneme

  // pauses inside the text (a group of adjacent pause phonemes counts as one) take the longest
  // remaining runs, matched in order to the nearest expected times
  std::vector<std::pair<std::size_t, std::size_t>> pauses;  // [first, last] token of each group
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (!is_pause(tok[i])) continue;
    std::size_t j = i;
    while (j + 1 < n && is_pause(tok[j + 1])) ++j;
    if (j + 1 < n) pauses.emplace_back(i, j);  // the final group is the end of the text
    i = j;
  }
  std::vector<std::size_t> candidates;
  for (std::size_t r = 0; r < runs.size(); ++r)
    if (!used[r]) candidates.push_back(r);
  std::stable_sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    return runs[a].e - runs[a].s > runs[b].e - runs[b].s;
  });
  if (candidates.size() > pauses.size()) candidates.resize(pauses.size());
  std::sort(candidates.begin(), candidates.end());
  {
    const std::vector<double> start = layout(anchors, weight);
    const auto centre_of = [&](std::size_t k) {
      return 0.5 * (start[pauses[k].first] + start[pauses[k].second + 1]);
    };
    std::size_t next = 0;  // first group not yet matched
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const Run& r = runs[candidates[c]];
      const double centre = 0.5 * (r.s + r.e);
      const std::size_t last =
          pauses.size() - (candidates.size() - c);  // leave groups for the rest
      std::size_t best = next;
      for (std::size_t k = next; k <= last; ++k)
        if (std::abs(centre_of(k) - centre) < std::abs(centre_of(best) - centre)) best = k;
      insert_anchor(anchors, pauses[best].first, r.s);
      insert_anchor(anchors, pauses[best].second + 1, r.e);
      used[candidates[c]] = 1;
      next = best + 1;
    }
  }
  // stop closures: a remaining run of silence ends where a stop starts
  {
    const std::vector<double> start = layout(anchors, weight);
    std::size_t next = 1;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      if (used[r]) continue;
      std::size_t best = n;
      for (std::size_t i = next; i < n; ++i) {
        if (!is_stop(tok[i])) continue;
        if (start[i] - runs[r].e > options.stop_tolerance) break;
        if (std::abs(start[i] - runs[r].e) <= options.stop_tolerance &&
            (best == n || std::abs(start[i] - runs[r].e) < std::abs(start[best] - runs[r].e)))
          best = i;
      }
      if (best == n) continue;
      // the anchor must keep the order of the anchors around it
      auto it = std::lower_bound(anchors.begin(), anchors.end(), std::make_pair(best, -1e300));
      const double lo = std::prev(it)->second;
      const double hi = it != anchors.end() ? it->second : total;
      if (runs[r].e > lo && runs[r].e < hi && (it == anchors.end() || it->first != best)) {
        insert_anchor(anchors, best, runs[r].e);
        next = best + 1;
      }
    }
  }
  const std::vector<double> start = layout(anchors, weight);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::min(start[i], total);
    const double e = i + 1 < n ? std::min(start[i + 1], total) : total;
    if (e > s) out.push_back({tok[i], s, e});
  }
  if (!out.empty()) {
    out.front().start = 0.0;
    out.back().end = total;
  }
  return out;
}

EspeakProgram::EspeakProgram(SpeechOptions options) : options_(std::move(options)) {
  options_.validate();
}

Utterance EspeakProgram::synthesize(std::string_view text) const {
  check_text(text);
  const std::string input(text);
  std::vector<std::string> common{options_.program,
                                  "-v",
                                  options_.voice,
                                  "-s",
                                  std::to_string(options_.rate),
                                  "-p",
                                  std::to_string(options_.pitch),
                                  "--stdin"};
  const auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> argv = common;
    argv.insert(argv.begin() + 1, extra.begin(), extra.end());
    core::ProcessResult r = core::run_process(argv, input);
    if (r.exit_code != 0 || r.err.find("rror") != std::string::npos) {
      std::string msg = r.err.substr(0, r.err.find('\n'));
      if (msg.find("voice") != std::string::npos)
        throw InvalidInput("speech: espeak-ng has no voice '" + options_.voice + "'");
      throw IoError("speech: " + options_.program + " failed (exit " + std::to_string(r.exit_code) +
                    (msg.empty() ? ")" : "): " + msg));
    }
    return r;
  };
  // -z: no final sentence pause, so the audio equals what libespeak-ng returned for the same text
  const core::ProcessResult wav = run({"-z", "--stdout"});
  const core::ProcessResult pho = run({"-q", "-x", "--sep= "});
  const WavAudio audio = parse_wav(wav.out, options_.program + " --stdout");
  Utterance u;
  u.sample_rate = audio.sample_rate;
  u.samples = audio.samples;
  u.phonemes = align_phonemes(parse_espeak_phonemes(pho.out), u.samples, u.sample_rate);
  if (u.phonemes.empty() && !u.samples.empty()) u.phonemes.push_back({"_", 0.0, u.duration()});
  return u;
}

void ExternalSpeech::add(std::string text, Utterance u) {
  check_text(text);
  if (!(u.sample_rate >= 1000 && u.sample_rate <= 384000))
    throw InvalidInput("external speech: sample rate must be in [1000, 384000]");
  double t = 0.0;
  for (const PhonemeTiming& p : u.phonemes) {
    if (p.phoneme.empty()) throw InvalidInput("external speech: empty phoneme name");
    if (!(std::isfinite(p.start) && std::isfinite(p.end)) || std::abs(p.start - t) > 1e-6 ||
        !(p.end > p.start))
      throw InvalidInput("external speech: phonemes of '" + text + "' are not contiguous from 0");
    t = p.end;
  }
  if (u.phonemes.empty()) throw InvalidInput("external speech: no phonemes for '" + text + "'");
  if (u.samples.empty())
    u.samples.assign(static_cast<std::size_t>(std::ceil(t * u.sample_rate)), 0);
  if (t > u.duration() + 1.0 / u.sample_rate)
    throw InvalidInput("external speech: phonemes of '" + text + "' end after the audio");
  if (u.phonemes.back().end < u.duration())
    u.phonemes.push_back({"_", u.phonemes.back().end, u.duration()});
  u.phonemes.back().end = u.duration();
  utterances_[std::move(text)] = std::move(u);
}

Utterance ExternalSpeech::synthesize(std::string_view text) const {
  const auto it = utterances_.find(text);
  if (it == utterances_.end())
    throw InvalidInput("external speech: no timing for the text '" + std::string(text) + "'");
  return it->second;
}

Utterance synthesize(std::string_view text, const SpeechOptions& options) {
  return EspeakProgram(options).synthesize(text);
}

std::vector<std::int16_t> place_utterances(const std::vector<Utterance>& utterances,
                                           const std::vector<double>& start_times, int sample_rate,
                                           double min_duration) {
  if (utterances.size() != start_times.size())
    throw InvalidInput("place_utterances: size mismatch");
  if (sample_rate <= 0) throw InvalidInput("place_utterances: bad sample rate");
  std::size_t total =
      static_cast<std::size_t>(std::ceil(std::max(0.0, min_duration) * sample_rate));
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (std::size_t i = 0; i < utterances.size(); ++i) {
    if (utterances[i].sample_rate != sample_rate)
      throw InvalidInput("place_utterances: sample rates differ");
    if (!(start_times[i] >= 0 && std::isfinite(start_times[i])))
      throw InvalidInput("place_utterances: bad start time");
    const auto first = static_cast<std::size_t>(std::llround(start_times[i] * sample_rate));
    spans.emplace_back(first, first + utterances[i].samples.size());
    total = std::max(total, spans.back().second);
  }
  std::vector<std::int16_t> out(total, 0);
  for (std::size_t i = 0; i < utterances.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (spans[i].first < spans[j].second && spans[j].first < spans[i].second)
        throw InvalidInput("place_utterances: utterances overlap");
    std::copy(utterances[i].samples.begin(), utterances[i].samples.end(),
              out.begin() + static_cast<std::ptrdiff_t>(spans[i].first));
  }
  return out;
}

std::string format_wav(const std::vector<std::int16_t>& samples, int sample_rate) {
  if (sample_rate <= 0) throw InvalidInput("wav: bad sample rate");
  // RIFF INFO list after the samples (readers that only know "fmt " and "data" skip it): ISFT =
  // software.
  std::string software(kGenerator);
  software.push_back('\0');
  if (software.size() % 2) software.push_back('\0');         // chunks are word-aligned
  const std::uint64_t list_bytes = 4 + 8 + software.size();  // "INFO" + ISFT header + text
  const std::uint64_t data_bytes = samples.size() * 2;
  if (data_bytes > 0xFFFFFFF0u - 36 - 8 - list_bytes) throw InvalidInput("wav: too long");
  std::string out;
  const auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  const auto u16 = [&](std::uint16_t v) {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>(v >> 8);
  };
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

WavAudio parse_wav(std::string_view b, const std::string& name) {
  const auto fail = [&](const std::string& m) -> WavAudio {
    throw FormatError({name, "", 0, 0}, m);
  };
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
      v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
    return v;
  };
  const auto u16 = [&](std::size_t at) {
    return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) |
                                      (static_cast<unsigned char>(b[at + 1]) << 8));
  };
  if (b.size() < 12 || b.substr(0, 4) != "RIFF" || b.substr(8, 4) != "WAVE")
    return fail("not a RIFF/WAVE file");
  std::size_t pos = 12;
  int channels = 0, rate = 0;
  bool fmt = false;
  while (pos + 8 <= b.size()) {
    const std::string_view id = b.substr(pos, 4);
    std::size_t size = u32(pos + 4);
    pos += 8;
    if (id == "fmt ") {
      if (size < 16 || pos + size > b.size()) return fail("truncated fmt chunk");
      const std::uint16_t format = u16(pos);
      channels = u16(pos + 2);
      rate = static_cast<int>(std::min<std::uint32_t>(u32(pos + 4), 1u << 30));
      const std::uint16_t bits = u16(pos + 14);
      if (format != 1)
        return fail("only PCM WAV is supported (format tag " + std::to_string(format) + ")");
      if (bits != 16)
        return fail("only 16-bit samples are supported (got " + std::to_string(bits) + ")");
      if (channels != 1 && channels != 2) return fail("only mono or stereo is supported");
      if (rate < 1000 || rate > 384000)
        return fail("sample rate " + std::to_string(rate) + " outside [1000, 384000]");
      fmt = true;
    } else if (id == "data") {
      if (!fmt) return fail("data chunk before the fmt chunk");
      // streamed WAVs (e.g. espeak-ng --stdout) carry a placeholder size: read to the end
      if (size == 0 || size > b.size() - pos) size = b.size() - pos;
      const std::size_t frame = 2 * static_cast<std::size_t>(channels);
      const std::size_t frames = size / frame;
      WavAudio w;
      w.sample_rate = rate;
      w.samples.resize(frames);
      for (std::size_t f = 0; f < frames; ++f) {
        int sum = 0;
        for (int c = 0; c < channels; ++c)
          sum += static_cast<std::int16_t>(u16(pos + f * frame + 2 * static_cast<std::size_t>(c)));
        w.samples[f] = static_cast<std::int16_t>(sum / channels);
      }
      return w;
    }
    if (size > b.size() - pos) return fail("truncated chunk '" + std::string(id) + "'");
    pos += size + (size % 2);
  }
  return fail(fmt ? "no data chunk" : "no fmt chunk");
}

WavAudio read_wav(const std::string& path) { return parse_wav(core::read_file(path), path); }

}  // namespace emoface::channels
