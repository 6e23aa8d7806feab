// Error paths of the C API: every bad call returns an error code with a message and never crashes
// (run under ASan/UBSan with -DEMOFACE_SANITIZE=ON); the good paths return the runtime's values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "emoface/emoface.h"

namespace {

struct Handle {
  emoface_character* c;
  explicit Handle(const char* config = nullptr) {
    char err[256] = "x";
    c = emoface_character_create(config, err, sizeof err);
  }
  ~Handle() { emoface_character_destroy(c); }
};

TEST(CApi, NamesAndCounts) {
  EXPECT_STREQ(emoface_version(), "0.1.0");
  EXPECT_EQ(emoface_parameter_count(), 42u);
  EXPECT_STREQ(emoface_parameter_name(0), "zygomatic_major_l");
  EXPECT_STREQ(emoface_parameter_name(41), "eye_blink_r");
  EXPECT_EQ(emoface_parameter_name(42), nullptr);
  EXPECT_STREQ(emoface_emotion_name(1), "happiness");
  EXPECT_EQ(emoface_emotion_name(6), nullptr);
  EXPECT_NE(emoface_arkit_name(51), nullptr);
  EXPECT_EQ(emoface_arkit_name(52), nullptr);
}

TEST(CApi, CreateFailuresReportThroughErrAndThreadLocal) {
  char err[64];
  for (const char* bad :
       {"{", "[1,2]", R"({"format": "emoface.character", "version": "1.0", "fps": -1})",
        R"({"format": "emoface.character", "version": "9.0"})",
        R"({"format": "emoface.character", "version": "1.0", "source": {"kind": "parlee"}})"}) {
    std::memset(err, 0, sizeof err);
    EXPECT_EQ(emoface_character_create(bad, err, sizeof err), nullptr) << bad;
    EXPECT_GT(std::strlen(err), 0u) << bad;
    EXPECT_LT(std::strlen(err), sizeof err);  // truncated, NUL-terminated
    EXPECT_GT(std::strlen(emoface_last_error()), 0u);
  }
  EXPECT_EQ(emoface_character_create("{", nullptr, 0), nullptr);  // no err buffer is fine
  char one[1] = {'x'};
  EXPECT_EQ(emoface_character_create("{", one, 1), nullptr);
  EXPECT_EQ(one[0], '\0');
  EXPECT_EQ(emoface_character_create_from_file(nullptr, err, sizeof err), nullptr);
  EXPECT_EQ(emoface_character_create_from_file("/no/such/file.json", err, sizeof err), nullptr);
  EXPECT_EQ(emoface_character_restore(nullptr, err, sizeof err), nullptr);
  EXPECT_EQ(emoface_character_restore("{\"format\": \"emoface.character_state\"}", err, sizeof err),
            nullptr);
}

TEST(CApi, NullHandlesNeverCrash) {
  double buf[64];
  float fbuf[8];
  char text[8];
  size_t needed = 0;
  EXPECT_EQ(emoface_character_event(nullptr, "{}"), EMOFACE_ERROR_ARGUMENT);
  EXPECT_STREQ(emoface_last_error(), "NULL character handle");
  EXPECT_EQ(emoface_character_update(nullptr, 0.1), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_speak(nullptr, "hi", nullptr), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_speak_timing(nullptr, "0\tX\n", nullptr), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_emotions(nullptr, buf, 6), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_parameters(nullptr, buf, 42), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_arkit(nullptr, buf, 52), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_times(nullptr, buf, buf, buf), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_vertex_count(nullptr), 0u);
  EXPECT_EQ(emoface_character_vertices(nullptr, fbuf, 8), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_snapshot(nullptr, text, sizeof text, &needed),
            EMOFACE_ERROR_ARGUMENT);
  EXPECT_STREQ(emoface_character_error(nullptr), "NULL character handle");
  emoface_character_destroy(nullptr);
}

TEST(CApi, BadArgumentsOnAHandle) {
  Handle h;
  ASSERT_NE(h.c, nullptr);
  double buf[64];
  EXPECT_EQ(emoface_character_event(h.c, nullptr), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_event(h.c, "not json"), EMOFACE_ERROR_SKIPPED);
  EXPECT_NE(std::string(emoface_character_error(h.c)).find("JSON"), std::string::npos);
  EXPECT_EQ(emoface_character_event(h.c, R"({"emotions": {"happiness": 1e300}})"),
            EMOFACE_ERROR_SKIPPED);
  EXPECT_EQ(emoface_character_event(h.c, R"j({"action": "(shot team)"})j"), EMOFACE_ERROR_SKIPPED);
  EXPECT_EQ(emoface_character_update(h.c, NAN), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_update(h.c, -1), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_update(h.c, INFINITY), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_emotions(h.c, buf, 5), EMOFACE_ERROR_SIZE);
  EXPECT_EQ(emoface_character_emotions(h.c, nullptr, 6), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_parameters(h.c, buf, 43), EMOFACE_ERROR_SIZE);
  EXPECT_NE(std::string(emoface_character_error(h.c)).find("42"), std::string::npos);
  EXPECT_EQ(emoface_character_arkit(h.c, buf, 51), EMOFACE_ERROR_SIZE);
  EXPECT_EQ(emoface_character_vertex_count(h.c), 0u);
  float f[3];
  EXPECT_EQ(emoface_character_vertices(h.c, f, 3), EMOFACE_ERROR_UNAVAILABLE);
  EXPECT_EQ(emoface_character_speak(h.c, nullptr, nullptr), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_speak(h.c, "   ", nullptr), EMOFACE_ERROR_ARGUMENT);
  EXPECT_EQ(emoface_character_speak_timing(h.c, "0\tQ\n", nullptr), EMOFACE_ERROR_FORMAT);
  EXPECT_EQ(emoface_character_speak_timing(h.c, "{\"mouthCues\": 5}", nullptr),
            EMOFACE_ERROR_FORMAT);
  EXPECT_EQ(emoface_character_speak_timing(h.c, "start\tend\tphoneme\n0\tnan\ta\n", nullptr),
            EMOFACE_ERROR_FORMAT);
  char small[4];
  size_t needed = 0;
  EXPECT_EQ(emoface_character_snapshot(h.c, small, sizeof small, &needed), EMOFACE_ERROR_SIZE);
  EXPECT_GT(needed, 100u);
  // after all that the handle still works
  EXPECT_EQ(emoface_character_event(h.c, R"({"emotions": {"anger": 0.8}})"), EMOFACE_OK);
  EXPECT_STREQ(emoface_character_error(h.c), "");
  EXPECT_EQ(emoface_character_update(h.c, 1.0), EMOFACE_OK);
  EXPECT_EQ(emoface_character_emotions(h.c, buf, 6), EMOFACE_OK);
  EXPECT_EQ(buf[2], 0.8);
}

TEST(CApi, ValuesSnapshotAndFace) {
  Handle h(R"({"format": "emoface.character", "version": "1.0", "face": "default", "seed": 2})");
  ASSERT_NE(h.c, nullptr) << emoface_last_error();
  ASSERT_EQ(emoface_character_event(h.c, R"({"emotions": {"surprise": 1}})"), EMOFACE_OK);
  for (int i = 0; i < 60; ++i) ASSERT_EQ(emoface_character_update(h.c, 1.0 / 60), EMOFACE_OK);
  double in = 0, out = 0, lat = 0;
  ASSERT_EQ(emoface_character_times(h.c, &in, &out, &lat), EMOFACE_OK);
  EXPECT_NEAR(in - out, lat, 1e-9);
  const size_t nv = emoface_character_vertex_count(h.c);
  ASSERT_GT(nv, 1000u);
  std::vector<float> v(3 * nv);
  EXPECT_EQ(emoface_character_vertices(h.c, v.data(), v.size() - 1), EMOFACE_ERROR_SIZE);
  ASSERT_EQ(emoface_character_vertices(h.c, v.data(), v.size()), EMOFACE_OK);
  for (float x : v) ASSERT_TRUE(std::isfinite(x));
  size_t needed = 0;
  emoface_character_snapshot(h.c, nullptr, 0, &needed);
  std::string snap(needed, '\0');
  ASSERT_EQ(emoface_character_snapshot(h.c, snap.data(), snap.size(), &needed), EMOFACE_OK);
  char err[256];
  emoface_character* r = emoface_character_restore(snap.c_str(), err, sizeof err);
  ASSERT_NE(r, nullptr) << err;
  double a[42], b[42];
  for (int i = 0; i < 30; ++i) {
    emoface_character_update(h.c, 0.02);
    emoface_character_update(r, 0.02);
    emoface_character_parameters(h.c, a, 42);
    emoface_character_parameters(r, b, 42);
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0);
  }
  emoface_character_destroy(r);
}

TEST(CApi, EmotionsToMusclesBatch) {
  const double esv[12] = {0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  double out[38];
  ASSERT_EQ(emoface_emotions_to_muscles(esv, 2, out, 38), EMOFACE_OK);
  EXPECT_GT(out[0], 0.3);                                // zygomatic major of full happiness
  for (int i = 19; i < 38; ++i) EXPECT_EQ(out[i], 0.0);  // zero emotion: neutral face
  EXPECT_EQ(emoface_emotions_to_muscles(esv, 2, out, 37), EMOFACE_ERROR_SIZE);
  EXPECT_EQ(emoface_emotions_to_muscles(nullptr, 2, out, 38), EMOFACE_ERROR_ARGUMENT);
  const double bad[6] = {0, NAN, 0, 0, 0, 0};
  EXPECT_EQ(emoface_emotions_to_muscles(bad, 1, out, 19), EMOFACE_ERROR_ARGUMENT);
  EXPECT_NE(std::string(emoface_last_error()).find("row 0"), std::string::npos);
  EXPECT_EQ(emoface_emotions_to_muscles(esv, SIZE_MAX / 2, out, 19), EMOFACE_ERROR_SIZE);
}

}  // namespace
