/* The C API's live mind-map character (issue 19 item 5), compiled as C99: a mindmotion character
 * from a motion graph file and a mind map file, stimuli, updates, parameters/ARKit/vertices, and
 * the error paths. Usage: capi_mindmotion_test GRAPH.json MAP.json */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "emoface/emoface.h"

static int failures = 0;

#define CHECK(cond)                                                  \
  do {                                                               \
    if (!(cond)) {                                                   \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                    \
    }                                                                \
  } while (0)

static const char* kOptions =
    "{\"format\": \"emoface.character\", \"version\": \"1.1\", \"seed\": 3,"
    " \"blinks\": false, \"gaze_noise\": false, \"head_noise\": false}";

static double largest_difference(const double* a, const double* b, size_t n) {
  double m = 0.0;
  size_t i;
  for (i = 0; i < n; ++i)
    if (fabs(a[i] - b[i]) > m) m = fabs(a[i] - b[i]);
  return m;
}

int main(int argc, char** argv) {
  char err[512];
  double rest[42], p[42], q[42], w[52];
  emoface_character *a, *b, *bad;
  int i;
  if (argc != 3) {
    fprintf(stderr, "usage: %s GRAPH.json MAP.json\n", argv[0]);
    return 2;
  }

  /* Creation failures: NULL paths, a missing graph file, options with a source of their own. */
  bad = emoface_character_create_mindmotion(NULL, argv[2], NULL, err, sizeof err);
  CHECK(bad == NULL && strstr(err, "graph") != NULL);
  bad = emoface_character_create_mindmotion(argv[1], NULL, NULL, err, sizeof err);
  CHECK(bad == NULL && strstr(err, "map") != NULL);
  bad = emoface_character_create_mindmotion("/no/such/graph.json", argv[2], NULL, err, sizeof err);
  CHECK(bad == NULL && strstr(err, "/no/such/graph.json") != NULL);
  CHECK(strcmp(emoface_last_error(), err) == 0);
  bad = emoface_character_create_mindmotion(argv[2], argv[2], NULL, err, sizeof err); /* a map */
  CHECK(bad == NULL && strlen(err) > 0);
  bad = emoface_character_create_mindmotion(
      argv[1], argv[2],
      "{\"format\": \"emoface.character\", \"version\": \"1.1\", \"source\": {\"kind\": "
      "\"parlee\", \"domain\": \"x\"}}",
      err, sizeof err);
  CHECK(bad == NULL && strlen(err) > 0);
  bad = emoface_character_create_mindmotion(argv[1], argv[2], "{", err, 4); /* truncated err */
  CHECK(bad == NULL && strlen(err) == 3);

  /* Two characters with the same options: the same stream. */
  a = emoface_character_create_mindmotion(argv[1], argv[2], kOptions, err, sizeof err);
  b = emoface_character_create_mindmotion(argv[1], argv[2], kOptions, err, sizeof err);
  if (!a || !b) {
    fprintf(stderr, "create failed: %s\n", err);
    return 1;
  }
  CHECK(emoface_character_update(a, 1.0) == EMOFACE_OK);
  CHECK(emoface_character_update(b, 1.0) == EMOFACE_OK);
  CHECK(emoface_character_parameters(a, rest, 42) == EMOFACE_OK);

  /* Stimuli: an action node of the map, one it lacks (skipped), one with weights (copied). */
  CHECK(emoface_character_stimulus(a, "insult", NULL) == EMOFACE_OK);
  CHECK(emoface_character_stimulus(b, "insult", NULL) == EMOFACE_OK);
  CHECK(emoface_character_stimulus(a, "tickle", NULL) == EMOFACE_ERROR_SKIPPED);
  CHECK(strstr(emoface_character_error(a), "tickle") != NULL);
  CHECK(emoface_character_stimulus(a, "tickle", "{\"happiness\": 1.5}") == EMOFACE_ERROR_SKIPPED);
  CHECK(emoface_character_stimulus(a, "tickle", "[1") == EMOFACE_ERROR_FORMAT);
  CHECK(emoface_character_stimulus(a, "tickle", "[1]") == EMOFACE_ERROR_FORMAT);
  CHECK(emoface_character_stimulus(a, NULL, NULL) == EMOFACE_ERROR_ARGUMENT);
  CHECK(emoface_character_stimulus(NULL, "insult", NULL) == EMOFACE_ERROR_ARGUMENT);
  CHECK(emoface_character_event(a, "{\"emotions\": {\"happiness\": 1}}") == EMOFACE_ERROR_SKIPPED);
  CHECK(emoface_character_update(a, NAN) == EMOFACE_ERROR_ARGUMENT);
  CHECK(emoface_character_update(a, INFINITY) == EMOFACE_ERROR_ARGUMENT);

  for (i = 0; i < 120; ++i) {
    CHECK(emoface_character_update(a, 1.0 / 60) == EMOFACE_OK);
    CHECK(emoface_character_update(b, 1.0 / 60) == EMOFACE_OK);
    CHECK(emoface_character_parameters(a, p, 42) == EMOFACE_OK);
    CHECK(emoface_character_parameters(b, q, 42) == EMOFACE_OK);
    CHECK(memcmp(p, q, sizeof p) == 0);
  }
  CHECK(largest_difference(p, rest, 42) > 0.05); /* the insult moved the face */
  CHECK(emoface_character_parameters(a, p, 41) == EMOFACE_ERROR_SIZE);
  CHECK(emoface_character_arkit(a, w, 52) == EMOFACE_OK);
  for (i = 0; i < 52; ++i) CHECK(w[i] >= 0.0 && w[i] <= 1.0);
  CHECK(emoface_character_vertex_count(a) == 0); /* no face in the options */
  CHECK(emoface_character_vertices(a, NULL, 0) == EMOFACE_ERROR_UNAVAILABLE);
  {
    size_t needed = 0;
    CHECK(emoface_character_snapshot(a, NULL, 0, &needed) != EMOFACE_OK); /* not yet */
    CHECK(strstr(emoface_character_error(a), "mindmotion") != NULL);
  }
  emoface_character_destroy(a);
  emoface_character_destroy(b);

  /* With a face: vertices move. */
  a = emoface_character_create_mindmotion(
      argv[1], argv[2],
      "{\"format\": \"emoface.character\", \"version\": \"1.1\", \"face\": \"generic\"}", err,
      sizeof err);
  CHECK(a != NULL);
  if (a) {
    const size_t n = 3 * emoface_character_vertex_count(a);
    float* v0 = (float*)malloc(n * sizeof(float));
    float* v1 = (float*)malloc(n * sizeof(float));
    double moved = 0.0;
    size_t k;
    CHECK(n > 0 && v0 && v1);
    CHECK(emoface_character_update(a, 0.5) == EMOFACE_OK);
    CHECK(emoface_character_vertices(a, v0, n) == EMOFACE_OK);
    CHECK(emoface_character_event(a, "{\"stimulus\": \"joke\"}") == EMOFACE_OK);
    CHECK(emoface_character_update(a, 1.5) == EMOFACE_OK);
    CHECK(emoface_character_vertices(a, v1, n) == EMOFACE_OK);
    CHECK(emoface_character_vertices(a, v1, n - 1) == EMOFACE_ERROR_SIZE);
    for (k = 0; k < n; ++k)
      if (fabs((double)v1[k] - (double)v0[k]) > moved) moved = fabs((double)v1[k] - v0[k]);
    CHECK(moved > 1e-4);
    free(v0);
    free(v1);
    emoface_character_destroy(a);
  }
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  else printf("capi mindmotion: all checks passed\n");
  return failures ? 1 : 0;
}
