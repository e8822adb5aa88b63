#include "litamin2/io/file_util.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "litamin2/io/io_error.hpp"

namespace litamin2::io {

namespace fs = std::filesystem;

namespace {

/// Opens `path` for a whole-file read, positioned at the start; its size in `size`.
std::ifstream open_whole_file(const std::string& path, std::size_t& size) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw IoError(path, "file does not exist");
  if (fs::is_directory(status)) throw IoError(path, "is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path, std::string("cannot open for reading: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) throw IoError(path, "cannot determine the file size");
  in.seekg(0, std::ios::beg);
  size = static_cast<std::size_t>(end);
  return in;
}

/// Reads `size` bytes of `in` into `data`.
void read_whole(std::ifstream& in, const std::string& path, char* data, std::size_t size) {
  if (size > 0 && !in.read(data, static_cast<std::streamsize>(size))) {
    throw IoError(path, "read error after " + std::to_string(in.gcount()) + " of " +
                            std::to_string(size) + " bytes");
  }
}

}  // namespace

std::string read_file_bytes(const std::string& path) {
  std::size_t size = 0;
  std::ifstream in = open_whole_file(path, size);
  std::string bytes;
  bytes.resize(size);
  read_whole(in, path, bytes.data(), size);
  return bytes;
}

FileBuffer read_file_buffer(const std::string& path) {
  std::size_t size = 0;
  std::ifstream in = open_whole_file(path, size);
  FileBuffer buffer;
  buffer.data.reset(new char[size > 0 ? size : 1]);  // default-initialised: not zeroed
  buffer.size = size;
  read_whole(in, path, buffer.data.get(), size);
  return buffer;
}

void write_file_bytes(const std::string& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  if (size > 0) out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw IoError(path, "write error (disk full or I/O error?)");
}

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    const bool last = end == std::string_view::npos;
    if (last) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (last) break;
    begin = end + 1;
  }
  return lines;
}

namespace {
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == '\n';
}
}  // namespace

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > begin) tokens.push_back(line.substr(begin, i - begin));
  }
  return tokens;
}

bool is_blank(std::string_view line) {
  for (char c : line) {
    if (!is_space(c)) return false;
  }
  return true;
}

std::optional<double> parse_double(std::string_view token) {
  // std::from_chars rejects a leading '+', which printf-style writers never emit but humans do.
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  // Out-of-range values (e.g. "1e999") are reported as errors rather than clamped.
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::optional<unsigned long long> parse_unsigned(std::string_view token) {
  if (token.empty()) return std::nullopt;
  unsigned long long value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

}  // namespace litamin2::io
