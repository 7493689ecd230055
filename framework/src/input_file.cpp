// Validated text input (raylab/input_file.h).
#include "raylab/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

#include "raylab/error.h"

namespace raylab {

namespace {

// Closes the descriptor on every path out of read_input_file
struct Fd {
    int fd;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

std::string describe_type(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string size_text(std::size_t bytes) {
    if (bytes >= (std::size_t(1) << 20)) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes >> 10) + " KiB";
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_chars) {
    static const char hex[] = "0123456789abcdef";
    std::string out;
    for (const char ch : text) {
        if (out.size() >= max_chars) {
            out += "...";
            break;
        }
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c >= 0x7f) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += ch;
        }
    }
    return out;
}

std::string where(const std::string& source, std::size_t line) {
    return source + ":" + std::to_string(line) + ": ";
}

namespace {

// Opens path without blocking and checks it: a regular file of at most max_bytes
int open_checked(const std::string& path, std::size_t max_bytes, struct stat& st) {
    const std::string name = printable(path);
    if (path.empty()) throw Error("an empty file name");
    Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
    if (f.fd < 0) throw Error(name + ": cannot open file (" + std::strerror(errno) + ")");
    if (::fstat(f.fd, &st) != 0)
        throw Error(name + ": cannot open file (" + std::strerror(errno) + ")");
    if (!S_ISREG(st.st_mode))
        throw Error(name + ": " + describe_type(st.st_mode) + ", not a regular file");
    if (static_cast<unsigned long long>(st.st_size) > max_bytes)
        throw Error(name + ": " + std::to_string(st.st_size) + " bytes, more than the " +
                    size_text(max_bytes) + " allowed");
    const int fd = f.fd;
    f.fd = -1;
    return fd;
}

}  // namespace

void check_input_file(const std::string& path, std::size_t max_bytes) {
    struct stat st {};
    const Fd f{open_checked(path, max_bytes, st)};
}

std::string read_input_file(const std::string& path, std::size_t max_bytes) {
    const std::string name = printable(path);
    struct stat st {};
    const Fd f{open_checked(path, max_bytes, st)};
    std::string data(static_cast<std::size_t>(st.st_size), '\0');
    std::size_t got = 0;
    while (got < data.size()) {
        const ssize_t n = ::read(f.fd, &data[got], data.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Error(name + ": cannot read (" + std::strerror(errno) + ")");
        if (n == 0) break;  // the file shrank meanwhile
        got += static_cast<std::size_t>(n);
    }
    data.resize(got);
    return data;
}

std::string text_encoding(std::string_view text) {
    // A byte order mark names the encoding (UTF-32LE's begins with UTF-16LE's)
    if (text.substr(0, 4) == std::string_view("\xFF\xFE\0\0", 4)) return "UTF-32LE";
    if (text.substr(0, 4) == std::string_view("\0\0\xFE\xFF", 4)) return "UTF-32BE";
    if (text.substr(0, 2) == "\xFF\xFE") return "UTF-16LE";
    if (text.substr(0, 2) == "\xFE\xFF") return "UTF-16BE";
    // Without one, the NUL bytes tell: OBJ, MTL and view files are mostly ASCII, so every
    // second (UTF-16) or three in four (UTF-32) bytes are NUL, at fixed places. A NUL
    // here and there in UTF-8 text fills no such pattern.
    const std::string_view head = text.substr(0, 1024);
    std::size_t zeros[4] = {0, 0, 0, 0}, count[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < head.size(); ++k) {
        ++count[k % 4];
        if (head[k] == '\0') ++zeros[k % 4];
    }
    // more than half of the bytes at these places of each group of four are NUL
    const auto mostly = [&](std::initializer_list<int> places) {
        std::size_t z = 0, n = 0;
        for (const int p : places)
            z += zeros[p], n += count[p];
        return n > 0 && 2 * z > n;
    };
    if (head.size() >= 4) {
        if (mostly({1}) && mostly({2}) && mostly({3}) && !mostly({0})) return "UTF-32LE";
        if (mostly({0}) && mostly({1}) && mostly({2}) && !mostly({3})) return "UTF-32BE";
    }
    if (head.size() >= 2) {
        if (mostly({1, 3}) && !mostly({0, 2})) return "UTF-16LE";
        if (mostly({0, 2}) && !mostly({1, 3})) return "UTF-16BE";
    }
    return "";
}

std::vector<std::string_view> split_lines(std::string_view text, std::size_t max_line,
                                          const std::string& source) {
    if (const std::string encoding = text_encoding(text); !encoding.empty()) {
        throw Error(source + ": the file is " + encoding +
                    " text; raylab reads UTF-8 (or ASCII): convert it, e.g. iconv -f " +
                    encoding + " -t UTF-8 OLD > NEW");
    }
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::vector<std::string_view> lines;
    while (!text.empty()) {
        std::size_t end = text.find('\n');
        const std::size_t next = end == std::string_view::npos ? text.size() : end + 1;
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(0, end);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (line.find('\r') != std::string_view::npos) {
            // Classic Mac line ends (CR only) would read as one long line of words
            throw Error(where(source, lines.size() + 1) +
                        "a carriage return (CR) inside the line: line ends must be LF "
                        "or CRLF, not CR alone");
        }
        if (line.size() > max_line) {
            throw Error(where(source, lines.size() + 1) + "line longer than " +
                        std::to_string(max_line) + " bytes");
        }
        lines.push_back(line);
        text.remove_prefix(next);
    }
    return lines;
}

Decimal parse_decimal(std::string_view w, float& out) {
    std::size_t k = 0;
    if (k < w.size() && (w[k] == '+' || w[k] == '-')) ++k;
    std::size_t digits = 0;
    while (k < w.size() && w[k] >= '0' && w[k] <= '9')
        ++k, ++digits;
    if (k < w.size() && w[k] == '.') {
        ++k;
        while (k < w.size() && w[k] >= '0' && w[k] <= '9')
            ++k, ++digits;
    }
    if (digits == 0) return Decimal::not_decimal;
    if (k < w.size() && (w[k] == 'e' || w[k] == 'E')) {
        ++k;
        if (k < w.size() && (w[k] == '+' || w[k] == '-')) ++k;
        std::size_t exp_digits = 0;
        while (k < w.size() && w[k] >= '0' && w[k] <= '9')
            ++k, ++exp_digits;
        if (exp_digits == 0) return Decimal::not_decimal;
    }
    if (k != w.size()) return Decimal::not_decimal;
    // glibc's strtod reads a decimal of any length exactly: only the float's range limits
    // it
    const std::string copy(w);
    const double x = std::strtod(copy.c_str(), nullptr);
    if (!(std::fabs(x) <= double(std::numeric_limits<float>::max())))
        return Decimal::out_of_range;
    out = static_cast<float>(x);
    return Decimal::ok;
}

bool parse_real(std::string_view w, float& out) {
    return parse_decimal(w, out) == Decimal::ok;
}

bool parse_whole(std::string_view w, long long lo, long long hi, long long& out) {
    std::size_t k = 0;
    const bool negative = !w.empty() && w[0] == '-';
    if (k < w.size() && (w[k] == '+' || w[k] == '-')) ++k;
    if (k == w.size()) return false;
    for (std::size_t j = k; j < w.size(); ++j)
        if (w[j] < '0' || w[j] > '9') return false;
    while (k + 1 < w.size() && w[k] == '0')  // leading zeros of any number
        ++k;
    // 18 digits always fit a long long; a longer number saturates, beyond every range
    // here
    long long x = 0;
    if (w.size() - k > 18) {
        x = std::numeric_limits<long long>::max();
    } else {
        for (; k < w.size(); ++k)
            x = 10 * x + (w[k] - '0');
    }
    out = negative ? -x : x;
    return out >= lo && out <= hi;
}

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t k = 0;
    while (k < line.size()) {
        while (k < line.size() && (line[k] == ' ' || line[k] == '\t'))
            ++k;
        const std::size_t start = k;
        while (k < line.size() && line[k] != ' ' && line[k] != '\t')
            ++k;
        if (k > start) words.push_back(line.substr(start, k - start));
    }
    return words;
}

}  // namespace raylab
