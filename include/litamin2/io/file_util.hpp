#pragma once
/// Small helpers shared by the readers of litamin2::io: whole-file reading, line splitting and
/// locale-independent number parsing. Every failure throws IoError naming the file.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace litamin2::io {

/// Reads a whole file into memory. Throws IoError if it does not exist, is a directory or
/// cannot be read completely.
std::string read_file_bytes(const std::string& path);

/// A whole file's bytes in a buffer that is not zeroed before the read (std::string's resize
/// zeroes it first: one more pass over a 2 MB scan's memory before the read's copy).
struct FileBuffer {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  std::string_view view() const { return std::string_view(data.get(), size); }
};

/// As read_file_bytes, into a FileBuffer: for large binary files read once (scans).
FileBuffer read_file_buffer(const std::string& path);

/// Writes `size` bytes to `path` (replacing it). Throws IoError if the file cannot be written.
void write_file_bytes(const std::string& path, const void* data, std::size_t size);

/// Splits text into lines, accepting "\n" and "\r\n" line ends (the "\r" is removed).
std::vector<std::string_view> split_lines(std::string_view text);

/// Splits a line into tokens separated by spaces, tabs, '\r', '\v' or '\f'.
std::vector<std::string_view> split_whitespace(std::string_view line);

/// True if the line holds only whitespace.
bool is_blank(std::string_view line);

/// Parses a whole token as a double ("1.5", "-2e-3", "+4", "nan", "inf"), independently of the
/// C locale. Returns std::nullopt if the token is not entirely a number.
std::optional<double> parse_double(std::string_view token);

/// Parses a whole token as a non-negative decimal integer; std::nullopt otherwise.
std::optional<unsigned long long> parse_unsigned(std::string_view token);

}  // namespace litamin2::io
