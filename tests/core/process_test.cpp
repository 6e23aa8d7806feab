#include "emoface/core/process.hpp"

#include <gtest/gtest.h>

#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

TEST(Process, EchoesLargeInputWithoutDeadlock) {
  std::string input(3 << 20, 'x');  // larger than any pipe buffer, both ways
  for (std::size_t i = 0; i < input.size(); i += 97) input[i] = static_cast<char>('a' + i % 26);
  const ProcessResult r = run_process({"cat"}, input);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, input);
  EXPECT_TRUE(r.err.empty());
}

TEST(Process, ExitCodesAndStandardError) {
  EXPECT_EQ(run_process({"false"}).exit_code, 1);
  const ProcessResult r = run_process({"sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");
  // arguments are passed as they are (no shell word splitting or expansion)
  EXPECT_EQ(run_process({"printf", "%s|", "a b", "$HOME"}).out, "a b|$HOME|");
}

TEST(Process, ProgramThatIgnoresItsInputDoesNotKillUs) {
  const ProcessResult r =
      run_process({"true"}, std::string(4 << 20, 'y'));  // SIGPIPE must not escape
  EXPECT_EQ(r.exit_code, 0);
}

TEST(Process, BadInput) {
  EXPECT_THROW(run_process({}), InvalidInput);
  EXPECT_THROW(run_process({""}), InvalidInput);
  EXPECT_THROW(run_process({"echo", std::string("a\0b", 3)}), InvalidInput);
  try {
    run_process({"emoface-no-such-program-xyz"});
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("emoface-no-such-program-xyz"), std::string::npos);
  }
  ProcessOptions small;
  small.max_output = 10;
  EXPECT_THROW(run_process({"cat"}, std::string(1000, 'z'), small), IoError);
  small.max_output = 0;
  EXPECT_THROW(run_process({"cat"}, "", small), InvalidInput);
}

}  // namespace
}  // namespace emoface::core
