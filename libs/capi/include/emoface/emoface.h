/* emoface C API (libemoface.so, pkg-config emoface): emotional characters for game engines and any
 * language with a C FFI (C#/P-Invoke, Unreal C++, Godot GDExtension, Python ctypes, Rust, ...).
 *
 *   emoface_character* c = emoface_character_create(NULL, err, sizeof err);   // NULL = defaults
 *   emoface_character_event(c, "{\"emotions\": {\"happiness\": 0.9}}");
 *   for (;;) {
 *     emoface_character_update(c, 1.0 / 60.0);
 *     double p[42];  emoface_character_parameters(c, p, 42);  // emoface_parameter_name(i)
 *   }
 *   emoface_character_destroy(c);
 *
 * Rules: handles are opaque; every int function returns EMOFACE_OK (0) on success, otherwise an
 * EMOFACE_ERROR_* code and a message in emoface_character_error(handle) (valid until the next call
 * on that handle) — or, without a handle (NULL handle, create/restore failures), in
 * emoface_last_error(), which is per thread. No C++ exception crosses this boundary. Buffers are
 * caller-owned: `n` is their capacity in elements; a wrong `n` is EMOFACE_ERROR_SIZE (nothing
 * written). A handle may be used from one thread at a time; different handles are independent.
 * Strings are UTF-8, NUL-terminated. Times are seconds.
 * See docs/runtime.md for the config and event JSON and for Unity, Unreal and Godot bindings.
 *
 * ABI: entry points are only ever added (the soname stays libemoface.so.0 while that holds);
 * emoface_character_create_mindmotion and emoface_character_stimulus were added after 0.1.0
 * (issue 19), every earlier function is unchanged.
 */
#ifndef EMOFACE_EMOFACE_H
#define EMOFACE_EMOFACE_H

#include <stddef.h>

#if defined(_WIN32)
#define EMOFACE_API __declspec(dllexport)
#elif defined(__GNUC__)
#define EMOFACE_API __attribute__((visibility("default")))
#else
#define EMOFACE_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

enum {
  EMOFACE_OK = 0,
  EMOFACE_ERROR_ARGUMENT = 1,    /* NULL handle or pointer, value out of range */
  EMOFACE_ERROR_FORMAT = 2,      /* malformed JSON or file content */
  EMOFACE_ERROR_IO = 3,          /* a file or program could not be read or run */
  EMOFACE_ERROR_SKIPPED = 4,     /* an event the character's model does not take: reported, skipped */
  EMOFACE_ERROR_SIZE = 5,        /* a buffer's capacity does not match (see the function) */
  EMOFACE_ERROR_UNAVAILABLE = 6, /* the character has no face (vertices) */
  EMOFACE_ERROR_INTERNAL = 7
};

#define EMOFACE_EMOTION_COUNT 6 /* sadness happiness anger fear disgust surprise */
#define EMOFACE_MUSCLE_COUNT 19 /* thesis Table 2.1 */
#define EMOFACE_ARKIT_COUNT 52

typedef struct emoface_character emoface_character;

/* "0.1.0" */
EMOFACE_API const char* emoface_version(void);
/* The calling thread's last error without a handle ("" if none). */
EMOFACE_API const char* emoface_last_error(void);

/* The output parameters: count (42) and names (muscles::parameter_names(): 35 face muscles by side,
 * eye_gaze_yaw/pitch, head_yaw/pitch/roll in radians, eye_blink_l/r); NULL when i is out of range. */
EMOFACE_API size_t emoface_parameter_count(void);
EMOFACE_API const char* emoface_parameter_name(size_t i);
/* ESV names in order: "sadness", ..., "surprise"; NULL when i >= 6. */
EMOFACE_API const char* emoface_emotion_name(size_t i);
/* ARKit blend-shape names (52, faceweights' "arkit" set); NULL when out of range. */
EMOFACE_API const char* emoface_arkit_name(size_t i);

/* A character from an "emoface.character" JSON config in memory (NULL or "" = defaults: direct
 * emotion input, no face). On failure returns NULL and writes a message to err (if err_size > 0;
 * truncated, always NUL-terminated) and to emoface_last_error(). */
EMOFACE_API emoface_character* emoface_character_create(const char* config_json, char* err, size_t err_size);
/* The same from a file (relative paths inside are resolved against its directory). */
EMOFACE_API emoface_character* emoface_character_create_from_file(const char* path, char* err, size_t err_size);
/* A character continuing exactly where emoface_character_snapshot() left off. */
EMOFACE_API emoface_character* emoface_character_restore(const char* snapshot_json, char* err, size_t err_size);
/* A live mind-map character whose face moves by motion-graph synthesis (the "mindmotion" source,
 * docs/runtime.md): graph_path = a motion graph (`mgraph build`; weight-space ARKit-52, or 2D
 * iBUG-68 landmarks fitted on the face), map_path = the character's mind map (emoface.mindmap),
 * options_json = NULL/"" or an "emoface.character" config without "source" for everything else
 * (face, fps, seed, blinks, ...). A missing file, a graph of the wrong kind or a map action the
 * graph cannot synthesize fails like emoface_character_create (message naming the file/field). */
EMOFACE_API emoface_character* emoface_character_create_mindmotion(const char* graph_path,
                                                                   const char* map_path,
                                                                   const char* options_json,
                                                                   char* err, size_t err_size);
/* NULL is fine. */
EMOFACE_API void emoface_character_destroy(emoface_character* c);
/* The last error of this handle ("" after a success); for NULL, emoface_last_error(). */
EMOFACE_API const char* emoface_character_error(const emoface_character* c);

/* One event (JSON): {"emotions": {"happiness": 0.9}} (direct source), {"action": "(shot team)",
 * "outcome": "goal"} (ParleE), {"stimulus": "gift", "weights": {...}} (mind map). An event the model
 * does not allow returns EMOFACE_ERROR_SKIPPED; the character stays usable. */
EMOFACE_API int emoface_character_event(emoface_character* c, const char* event_json);
/* A mind-map stimulus at the input clock (mindmap and mindmotion sources): an action node of the
 * map, or with weights_json (NULL or {"happiness": 0.8, ...}, weights in [0, 1]) a world stimulus
 * the map may lack. Unknown stimuli and other sources: EMOFACE_ERROR_SKIPPED; malformed
 * weights_json: EMOFACE_ERROR_FORMAT. */
EMOFACE_API int emoface_character_stimulus(emoface_character* c, const char* stimulus,
                                           const char* weights_json);
/* Speaks text with the espeak-ng program (a separate process; tens of ms). *start_seconds (may be
 * NULL) receives the start on the input clock: play the audio at start + latency. */
EMOFACE_API int emoface_character_speak(emoface_character* c, const char* text, double* start_seconds);
/* Speaks with external timings (emoface timing TSV/JSON or Rhubarb Lip Sync TSV/JSON text, in memory;
 * docs/formats.md) for audio the host plays itself. */
EMOFACE_API int emoface_character_speak_timing(emoface_character* c, const char* timing_text, double* start_seconds);
/* Advances the input clock by dt seconds (finite, 0 <= dt <= 3600). */
EMOFACE_API int emoface_character_update(emoface_character* c, double dt_seconds);

/* Outputs at the output clock (input clock minus the latency): n must be exactly the count. */
EMOFACE_API int emoface_character_emotions(const emoface_character* c, double* out, size_t n /* 6 */);
EMOFACE_API int emoface_character_parameters(const emoface_character* c, double* out, size_t n /* 42 */);
EMOFACE_API int emoface_character_arkit(emoface_character* c, double* out, size_t n /* 52 */);
EMOFACE_API int emoface_character_times(const emoface_character* c, double* input_time, double* output_time,
                                        double* latency);

/* Deformed face (config "face": "default" or a rig file): vertex count (0 without a face) and
 * positions, 3 floats per vertex (x y z, metres), n = 3 * vertex count. */
EMOFACE_API size_t emoface_character_vertex_count(const emoface_character* c);
EMOFACE_API int emoface_character_vertices(emoface_character* c, float* out, size_t n);

/* The whole state as JSON. Call with out = NULL (or too small) to learn the size: *needed receives
 * the byte count including the NUL; returns EMOFACE_ERROR_SIZE when out_size < *needed. */
EMOFACE_API int emoface_character_snapshot(const emoface_character* c, char* out, size_t out_size, size_t* needed);

/* Batch: rows ESVs (rows x 6, ESV order, in [0,1]) -> rows x 19 muscle contractions (thesis Table 2.1
 * order) through the default fuzzy rules. out_n must be rows * 19. Errors go to emoface_last_error(). */
EMOFACE_API int emoface_emotions_to_muscles(const double* esv, size_t rows, double* out, size_t out_n);

#ifdef __cplusplus
}
#endif

#endif /* EMOFACE_EMOFACE_H */
