// The message log (viewer/log.h).
#include "log.h"

#include <cstdio>
#include <ctime>

namespace raylab::viewer {

void Log::add(const std::string& line) {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char stamp[16];
    std::strftime(stamp, sizeof stamp, "[%H:%M:%S] ", &local);
    lines_.push_back(stamp + line);
    if (lines_.size() > kMaxLines) lines_.pop_front();
    if (echo) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    }
}

std::string Log::text() const {
    std::string text;
    for (const std::string& line : lines_)
        text += line + "\n";
    return text;
}

}  // namespace raylab::viewer
