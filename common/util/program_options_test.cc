#include "common/util/program_options.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <memory>
#include <sstream>
#include <string>

namespace evoslam {
namespace {

std::string Logged(bool terminal) {
  std::ostringstream out;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_st>(out);
  spdlog::logger logger("test", sink);
  logger.set_pattern(LogPattern(terminal));
  logger.warn("a warning");
  return out.str();
}

// On a terminal a log line clears the progress bar's line before it is written, so that the
// two do not run together; in a pipe or a file the line is plain text.
TEST(LogPatternTest, ClearsTheLineOnATerminalOnly) {
  const std::string terminal = Logged(true), pipe = Logged(false);
  EXPECT_EQ(terminal.rfind("\r\033[K[", 0), 0u) << terminal;
  EXPECT_EQ(pipe.rfind("[", 0), 0u) << pipe;
  EXPECT_EQ(pipe.find('\033'), std::string::npos) << pipe;
  EXPECT_EQ(terminal.substr(terminal.find("] [")), pipe.substr(pipe.find("] [")));
  EXPECT_NE(pipe.find("] [warning] a warning"), std::string::npos) << pipe;
}

}  // namespace
}  // namespace evoslam
