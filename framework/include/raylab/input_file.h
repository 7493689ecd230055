// raylab/input_file.h: the one validated way to read a text input (OBJ, MTL, view file).
//
// Only regular files are opened (never a FIFO, device or folder: a FIFO would block, a
// device such as /dev/zero would never end), with a size cap per kind of file and a cap
// on every line. Text is UTF-8 (or ASCII): a UTF-8 byte order mark is dropped, UTF-16 and
// UTF-32 are refused by name, and CRLF line ends read as LF.
// Numbers are parsed strictly: decimal only, finite, nothing after them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace raylab {

/// Caps (docs/input.md, "Input limits").
constexpr std::size_t kMaxObjBytes = std::size_t(512) << 20;  ///< OBJ: 512 MiB
constexpr std::size_t kMaxMtlBytes = std::size_t(16) << 20;   ///< MTL: 16 MiB
constexpr std::size_t kMaxViewBytes = std::size_t(64) << 10;  ///< view file: 64 KiB
constexpr std::size_t kMaxObjLine = std::size_t(4) << 20;     ///< OBJ line: 4 MiB
constexpr std::size_t kMaxLine = 4096;                        ///< MTL and view lines

/// The bytes of the regular file at path, at most max_bytes. Opens with O_NONBLOCK and
/// checks the open file (fstat), so a FIFO or device is refused without blocking.
/// Throws raylab::Error "PATH: problem" (PATH escaped, see printable).
std::string read_input_file(const std::string& path, std::size_t max_bytes);

/// The checks of read_input_file without reading: a regular file, openable, at most
/// max_bytes. Throws raylab::Error.
void check_input_file(const std::string& path, std::size_t max_bytes);

/// "UTF-16LE", "UTF-16BE", "UTF-32LE" or "UTF-32BE" when text is in one of them (from its
/// byte order mark, or without one from where its NUL bytes fall); "" otherwise.
std::string text_encoding(std::string_view text);

/// The lines of text: a leading UTF-8 BOM dropped, a CR before each LF dropped. Throws
/// raylab::Error "SOURCE: the file is UTF-16LE text; ..." for UTF-16 or UTF-32 text
/// (text_encoding), "SOURCE:LINE: line longer than N bytes" past max_line.
std::vector<std::string_view> split_lines(std::string_view text, std::size_t max_line,
                                          const std::string& source);

/// text with control characters, DEL and bytes >= 0x80 written as \xNN, shortened to
/// max_chars (then "..."): safe to print to a terminal.
std::string printable(std::string_view text, std::size_t max_chars = 200);

/// How a word reads as a number (parse_decimal).
enum class Decimal { ok, not_decimal, out_of_range };

/// Strict decimal number: [+-]digits[.digits][(e|E)[+-]digits], of any length, finite as
/// a float. not_decimal for nan, inf, hex, blanks, junk or an empty word; out_of_range
/// beyond
/// +-3.4e38. The one number reader of flags, view files, OBJ and MTL files.
Decimal parse_decimal(std::string_view word, float& out);

/// parse_decimal(word, out) == Decimal::ok
bool parse_real(std::string_view word, float& out);

/// Strict whole number in [lo, hi] (decimal, optional sign).
bool parse_whole(std::string_view word, long long lo, long long hi, long long& out);

/// The words of a line, split on spaces and tabs.
std::vector<std::string_view> split_words(std::string_view line);

/// Errors while reading a file are "SOURCE:LINE: message" or "SOURCE:LINE: FIELD: ...".
std::string where(const std::string& source, std::size_t line);

}  // namespace raylab
