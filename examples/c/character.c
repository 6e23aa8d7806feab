/* A C99 program using the installed emoface C API (build: see examples/c/README.md):
 * a character smiles, is surprised, speaks from external (Rhubarb Lip Sync) timings, is saved and
 * restored, and continues exactly as the original. Exits non-zero when a result is wrong. */
#include <emoface/emoface.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

static void check(int ok, const char* what) {
  printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) ++failures;
}

static size_t param_index(const char* name) {
  for (size_t i = 0; i < emoface_parameter_count(); ++i)
    if (strcmp(emoface_parameter_name(i), name) == 0) return i;
  return (size_t)-1;
}

int main(void) {
  char err[256];
  const char* config =
      "{\"format\": \"emoface.character\", \"version\": \"1.0\", \"fps\": 60, \"seed\": 3}";
  emoface_character* c = emoface_character_create(config, err, sizeof err);
  if (!c) {
    fprintf(stderr, "create failed: %s\n", err);
    return 1;
  }
  printf("emoface %s, %zu parameters\n", emoface_version(), emoface_parameter_count());
  check(emoface_parameter_count() == 42, "42 face parameters");

  check(emoface_character_event(c, "{\"emotions\": {\"happiness\": 0.9}}") == EMOFACE_OK, "happiness event");
  check(emoface_character_event(c, "{\"emotions\": {\"joy\": 1}}") == EMOFACE_ERROR_SKIPPED,
        "unknown emotion is skipped");
  printf("     (%s)\n", emoface_character_error(c));
  for (int i = 0; i < 120; ++i) emoface_character_update(c, 1.0 / 60.0);

  double p[42], e[6], w[EMOFACE_ARKIT_COUNT];
  check(emoface_character_parameters(c, p, 42) == EMOFACE_OK, "parameters");
  check(emoface_character_emotions(c, e, 6) == EMOFACE_OK && e[1] == 0.9, "happiness shown after the latency");
  const size_t zyg = param_index("zygomatic_major_l");
  printf("     zygomatic_major_l = %.3f\n", p[zyg]);
  check(p[zyg] > 0.3, "the smile contracts the zygomatic major");
  check(emoface_character_arkit(c, w, EMOFACE_ARKIT_COUNT) == EMOFACE_OK, "ARKit weights");
  check(emoface_character_parameters(c, p, 41) == EMOFACE_ERROR_SIZE, "a wrong buffer size is refused");

  /* speech from Rhubarb Lip Sync's TSV (shapes A-H, X), audio played by the host */
  double start = -1;
  check(emoface_character_speak_timing(c, "0.00\tX\n0.10\tD\n0.30\tF\n0.50\tA\n0.60\tX\n", &start) == EMOFACE_OK,
        "speech from Rhubarb timings");
  printf("     speech starts at %.2f s (input clock)\n", start);
  for (int i = 0; i < 30; ++i) emoface_character_update(c, 1.0 / 60.0);

  /* snapshot, restore, and continue both: the outputs stay identical */
  size_t needed = 0;
  emoface_character_snapshot(c, NULL, 0, &needed);
  char* snap = malloc(needed);
  check(snap && emoface_character_snapshot(c, snap, needed, &needed) == EMOFACE_OK, "snapshot");
  emoface_character* d = emoface_character_restore(snap, err, sizeof err);
  check(d != NULL, "restore");
  free(snap);
  int same = d != NULL;
  double jaw = 0;
  for (int i = 0; i < 90 && d; ++i) {
    double a[42], b[42];
    emoface_character_update(c, 1.0 / 60.0);
    emoface_character_update(d, 1.0 / 60.0);
    emoface_character_parameters(c, a, 42);
    emoface_character_parameters(d, b, 42);
    same &= memcmp(a, b, sizeof a) == 0;
    if (a[param_index("masseter")] > jaw) jaw = a[param_index("masseter")];
  }
  check(same, "the restored character continues bit-identically");
  check(jaw > 0.2, "the jaw opens for the D (wide open) mouth shape");

  check(emoface_character_update(NULL, 0.1) == EMOFACE_ERROR_ARGUMENT, "NULL handle is an error, not a crash");
  check(emoface_character_create("{\"format\": 1}", err, sizeof err) == NULL, "bad config is refused");
  printf("     (%s)\n", err);
  emoface_character_destroy(d);
  emoface_character_destroy(c);
  printf("%s\n", failures ? "FAILED" : "all good");
  return failures ? 1 : 0;
}
