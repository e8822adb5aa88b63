#pragma once
/// The single exception type of the I/O layer.

#include <stdexcept>
#include <string>

namespace litamin2::io {

/// Thrown by every reader and writer of litamin2::io when a file is missing, unreadable,
/// truncated, corrupt or cannot be written. what() is "<path>: <what is wrong>".
class IoError : public std::runtime_error {
 public:
  /// Builds the message "<path>: <message>".
  IoError(const std::string& path, const std::string& message)
      : std::runtime_error(path + ": " + message), path_(path) {}

  /// The file (or folder) the error is about, as given by the caller.
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

}  // namespace litamin2::io
