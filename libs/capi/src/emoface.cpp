// The C ABI over emoface::runtime (emoface/emoface.h). Every entry point catches everything: no
// exception crosses into C.
#include "emoface/emoface.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <string>

#include "emoface/channels/speech.hpp"
#include "emoface/channels/timing_io.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/parlee/emotion.hpp"
#include "emoface/runtime/character.hpp"

struct emoface_character {
  emoface::runtime::Character character;
  mutable std::string error;
};

namespace {

namespace rt = emoface::runtime;

thread_local std::string g_last_error;

int code_of(const std::exception& e) {
  if (dynamic_cast<const emoface::FormatError*>(&e)) return EMOFACE_ERROR_FORMAT;
  if (dynamic_cast<const emoface::IoError*>(&e)) return EMOFACE_ERROR_IO;
  if (dynamic_cast<const emoface::InvalidInput*>(&e)) return EMOFACE_ERROR_ARGUMENT;
  if (dynamic_cast<const std::bad_alloc*>(&e)) return EMOFACE_ERROR_INTERNAL;
  if (dynamic_cast<const emoface::Error*>(&e)) return EMOFACE_ERROR_FORMAT;
  return EMOFACE_ERROR_INTERNAL;
}

// Runs f with the handle's error slot; exceptions become codes and messages.
template <class F>
int guarded(const emoface_character* c, F&& f) {
  if (!c) {
    g_last_error = "NULL character handle";
    return EMOFACE_ERROR_ARGUMENT;
  }
  c->error.clear();
  try {
    return f();
  } catch (const std::exception& e) {
    c->error = e.what();
    return code_of(e);
  } catch (...) {
    c->error = "unknown error";
    return EMOFACE_ERROR_INTERNAL;
  }
}

int fail(const emoface_character* c, int code, const std::string& message) {
  c->error = message;
  return code;
}

void write_err(char* err, std::size_t size, const std::string& message) {
  g_last_error = message;
  if (err && size > 0) {
    const std::size_t n = std::min(size - 1, message.size());
    std::memcpy(err, message.data(), n);
    err[n] = '\0';
  }
}

template <class F>
emoface_character* create(char* err, std::size_t err_size, F&& make) {
  write_err(err, err_size, "");
  try {
    return new emoface_character{make(), {}};
  } catch (const std::exception& e) {
    write_err(err, err_size, e.what());
  } catch (...) {
    write_err(err, err_size, "unknown error");
  }
  return nullptr;
}

int copy_out(const emoface_character* c, const double* src, std::size_t count, double* out,
             std::size_t n, const char* what) {
  if (!out) return fail(c, EMOFACE_ERROR_ARGUMENT, std::string(what) + ": NULL output buffer");
  if (n != count)
    return fail(c, EMOFACE_ERROR_SIZE,
                std::string(what) + ": the buffer must hold " + std::to_string(count) +
                    " values (got " + std::to_string(n) + ")");
  std::copy(src, src + count, out);
  return EMOFACE_OK;
}

}  // namespace

extern "C" {

const char* emoface_version(void) { return emoface::kVersion; }
const char* emoface_last_error(void) { return g_last_error.c_str(); }

size_t emoface_parameter_count(void) { return rt::Character::parameter_names().size(); }
const char* emoface_parameter_name(size_t i) {
  const auto& n = rt::Character::parameter_names();
  return i < n.size() ? n[i].c_str() : nullptr;
}
const char* emoface_emotion_name(size_t i) {
  return i < emoface::parlee::kBasicEmotionNames.size()
             ? emoface::parlee::kBasicEmotionNames[i].data()
             : nullptr;
}
const char* emoface_arkit_name(size_t i) {
  try {
    const auto& n = rt::Character::arkit_names();
    return i < n.size() ? n[i].c_str() : nullptr;
  } catch (...) {
    return nullptr;
  }
}

emoface_character* emoface_character_create(const char* config_json, char* err, size_t err_size) {
  return create(err, err_size, [&] {
    if (!config_json || !*config_json) return rt::Character(rt::CharacterConfig{});
    return rt::Character(rt::parse_character_config(config_json, "<config>"));
  });
}

emoface_character* emoface_character_create_from_file(const char* path, char* err,
                                                      size_t err_size) {
  return create(err, err_size, [&] {
    if (!path) throw emoface::InvalidInput("NULL config path");
    return rt::Character(rt::read_character_config(path));
  });
}

emoface_character* emoface_character_restore(const char* snapshot_json, char* err,
                                             size_t err_size) {
  return create(err, err_size, [&] {
    if (!snapshot_json) throw emoface::InvalidInput("NULL snapshot");
    return rt::restore_character(snapshot_json, "<snapshot>");
  });
}

emoface_character* emoface_character_create_mindmotion(const char* graph_path, const char* map_path,
                                                       const char* options_json, char* err,
                                                       size_t err_size) {
  return create(err, err_size, [&] {
    if (!graph_path) throw emoface::InvalidInput("NULL graph path");
    if (!map_path) throw emoface::InvalidInput("NULL mind map path");
    rt::CharacterConfig base;
    if (options_json && *options_json) base = rt::parse_character_config(options_json, "<options>");
    return rt::Character(rt::mindmotion_config(graph_path, map_path, std::move(base)));
  });
}

void emoface_character_destroy(emoface_character* c) { delete c; }

const char* emoface_character_error(const emoface_character* c) {
  return c ? c->error.c_str() : g_last_error.c_str();
}

int emoface_character_event(emoface_character* c, const char* event_json) {
  return guarded(c, [&]() -> int {
    if (!event_json) return fail(c, EMOFACE_ERROR_ARGUMENT, "NULL event");
    const rt::EventResult r = c->character.push_event(event_json);
    if (!r.applied) return fail(c, EMOFACE_ERROR_SKIPPED, r.message);
    return EMOFACE_OK;
  });
}

int emoface_character_stimulus(emoface_character* c, const char* stimulus,
                               const char* weights_json) {
  return guarded(c, [&]() -> int {
    if (!stimulus) return fail(c, EMOFACE_ERROR_ARGUMENT, "NULL stimulus");
    nlohmann::ordered_json event = {{"stimulus", stimulus}};
    if (weights_json) {
      nlohmann::ordered_json w;
      try {
        w = nlohmann::ordered_json::parse(weights_json);
      } catch (const std::exception& e) {
        return fail(c, EMOFACE_ERROR_FORMAT, std::string("weights: not valid JSON: ") + e.what());
      }
      if (!w.is_object())
        return fail(c, EMOFACE_ERROR_FORMAT, "weights: expected an object of emotion: weight");
      event["weights"] = std::move(w);
    }
    const rt::EventResult r = c->character.push_event(event.dump());
    if (!r.applied) return fail(c, EMOFACE_ERROR_SKIPPED, r.message);
    return EMOFACE_OK;
  });
}

int emoface_character_speak(emoface_character* c, const char* text, double* start_seconds) {
  return guarded(c, [&]() -> int {
    if (!text) return fail(c, EMOFACE_ERROR_ARGUMENT, "NULL text");
    double start = 0;
    c->character.speak(text, &start);
    if (start_seconds) *start_seconds = start;
    return EMOFACE_OK;
  });
}

int emoface_character_speak_timing(emoface_character* c, const char* timing_text,
                                   double* start_seconds) {
  return guarded(c, [&]() -> int {
    if (!timing_text) return fail(c, EMOFACE_ERROR_ARGUMENT, "NULL timing");
    const std::string text(timing_text);
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    emoface::channels::SpeechTiming t;
    if (first != std::string::npos && text[first] == '{') {
      t = text.find("\"mouthCues\"") != std::string::npos
              ? emoface::channels::rhubarb_to_visemes(
                    emoface::channels::parse_rhubarb_json(text, "<timing>"))
              : emoface::channels::parse_timing_json(text, "<timing>");
    } else if (text.find("start\t") != std::string::npos) {
      t = emoface::channels::parse_timing_tsv(text, "<timing>");
    } else {
      t = emoface::channels::rhubarb_to_visemes(
          emoface::channels::parse_rhubarb_tsv(text, "<timing>"));
    }
    const double start = c->character.speak(emoface::channels::external_utterance(t));
    if (start_seconds) *start_seconds = start;
    return EMOFACE_OK;
  });
}

int emoface_character_update(emoface_character* c, double dt_seconds) {
  return guarded(c, [&]() -> int {
    c->character.update(dt_seconds);
    return EMOFACE_OK;
  });
}

int emoface_character_emotions(const emoface_character* c, double* out, size_t n) {
  return guarded(c, [&]() -> int {
    const auto& e = c->character.emotions();
    return copy_out(c, e.data(), e.size(), out, n, "emotions");
  });
}

int emoface_character_parameters(const emoface_character* c, double* out, size_t n) {
  return guarded(c, [&]() -> int {
    const auto& p = c->character.parameters();
    return copy_out(c, p.data(), p.size(), out, n, "parameters");
  });
}

int emoface_character_arkit(emoface_character* c, double* out, size_t n) {
  return guarded(c, [&]() -> int {
    if (!out) return fail(c, EMOFACE_ERROR_ARGUMENT, "arkit: NULL output buffer");
    if (n != EMOFACE_ARKIT_COUNT)
      return fail(c, EMOFACE_ERROR_SIZE, "arkit: the buffer must hold 52 values");
    const auto& w = c->character.arkit();
    return copy_out(c, w.data(), w.size(), out, n, "arkit");
  });
}

int emoface_character_times(const emoface_character* c, double* input_time, double* output_time,
                            double* latency) {
  return guarded(c, [&]() -> int {
    if (input_time) *input_time = c->character.input_time();
    if (output_time) *output_time = c->character.output_time();
    if (latency) *latency = c->character.latency();
    return EMOFACE_OK;
  });
}

size_t emoface_character_vertex_count(const emoface_character* c) {
  if (!c) {
    g_last_error = "NULL character handle";
    return 0;
  }
  try {
    return c->character.has_face() ? static_cast<size_t>(c->character.mesh().vertices.rows()) : 0;
  } catch (...) {
    return 0;
  }
}

int emoface_character_vertices(emoface_character* c, float* out, size_t n) {
  return guarded(c, [&]() -> int {
    if (!c->character.has_face())
      return fail(c, EMOFACE_ERROR_UNAVAILABLE,
                  "vertices: the character has no face (config \"face\")");
    if (!out) return fail(c, EMOFACE_ERROR_ARGUMENT, "vertices: NULL output buffer");
    const std::size_t want = 3 * static_cast<std::size_t>(c->character.mesh().vertices.rows());
    if (n != want)
      return fail(c, EMOFACE_ERROR_SIZE,
                  "vertices: the buffer must hold " + std::to_string(want) + " floats");
    const auto& v = c->character.vertices();
    for (Eigen::Index i = 0; i < v.rows(); ++i)
      for (int k = 0; k < 3; ++k)
        out[3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(k)] =
            static_cast<float>(v(i, k));
    return EMOFACE_OK;
  });
}

int emoface_character_snapshot(const emoface_character* c, char* out, size_t out_size,
                               size_t* needed) {
  return guarded(c, [&]() -> int {
    const std::string s = c->character.snapshot();
    if (needed) *needed = s.size() + 1;
    if (!out || out_size < s.size() + 1)
      return fail(c, EMOFACE_ERROR_SIZE,
                  "snapshot: the buffer needs " + std::to_string(s.size() + 1) + " bytes");
    std::memcpy(out, s.c_str(), s.size() + 1);
    return EMOFACE_OK;
  });
}

int emoface_emotions_to_muscles(const double* esv, size_t rows, double* out, size_t out_n) {
  try {
    if (!esv || !out) {
      g_last_error = "emotions_to_muscles: NULL buffer";
      return EMOFACE_ERROR_ARGUMENT;
    }
    if (rows > (SIZE_MAX / 64) || out_n != rows * EMOFACE_MUSCLE_COUNT) {
      g_last_error = "emotions_to_muscles: out_n must be rows * 19";
      return EMOFACE_ERROR_SIZE;
    }
    static const emoface::fuzzyexpr::Engine engine;
    for (std::size_t r = 0; r < rows; ++r) {
      emoface::fuzzyexpr::Esv e{};
      for (std::size_t k = 0; k < 6; ++k) {
        const double v = esv[r * 6 + k];
        if (!(v >= 0 && v <= 1)) {
          g_last_error = "emotions_to_muscles: row " + std::to_string(r) + ", emotion " +
                         std::to_string(k) + ": intensity must be in [0, 1]";
          return EMOFACE_ERROR_ARGUMENT;
        }
        e[k] = v;
      }
      const auto f = engine.convert(e, r);
      std::copy(f.begin(), f.end(), out + r * EMOFACE_MUSCLE_COUNT);
    }
    g_last_error.clear();
    return EMOFACE_OK;
  } catch (const std::exception& e) {
    g_last_error = e.what();
    return code_of(e);
  } catch (...) {
    g_last_error = "unknown error";
    return EMOFACE_ERROR_INTERNAL;
  }
}

}  // extern "C"
