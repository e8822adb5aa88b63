#pragma once
/// The single exception type of the keyframe store.

#include <stdexcept>
#include <string>

namespace litamin2::store {

/// Thrown by KeyframeStore when its file is missing, is not a keyframe store (not SQLite,
/// truncated, another application's database, an unknown schema version), holds a corrupt row,
/// cannot be written, or when it is given a keyframe it cannot store. what() is
/// "<path>: <what is wrong>".
class StoreError : public std::runtime_error {
 public:
  /// Builds the message "<path>: <message>".
  StoreError(const std::string& path, const std::string& message)
      : std::runtime_error(path + ": " + message), path_(path) {}

  /// The store file the error is about, as given to KeyframeStore::open.
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

}  // namespace litamin2::store
