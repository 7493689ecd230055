// viewer/log.h: the viewer's message log, shown in the panel, echoed to stdout and
// saved with a bug report.
#pragma once

#include <deque>
#include <string>

namespace raylab::viewer {

class Log {
  public:
    /// Adds "[hh:mm:ss] line"; echoes it to stdout (flushed: tests read it) when echo.
    void add(const std::string& line);
    const std::deque<std::string>& lines() const { return lines_; }
    /// All lines, newline-terminated.
    std::string text() const;
    bool echo = true;

  private:
    static constexpr size_t kMaxLines = 1000;
    std::deque<std::string> lines_;
};

}  // namespace raylab::viewer
