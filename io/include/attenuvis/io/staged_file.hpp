// Output files that appear whole or not at all.
//
// A StagedFile is written under a unique temporary name in the destination's
// directory and renamed onto the destination by commit(): rename(2) within one
// file system is atomic, so a reader never sees a half-written file and a
// failed run leaves the old file (or none) in place.  The temporary is created
// with open(O_CREAT | O_EXCL, 0666) rather than mkstemp, whose 0600 mode would
// survive the rename: the result gets the permissions the umask allows.
//
// A destination that exists but is not a regular file (a device such as
// /dev/full, a directory, a FIFO) is refused before anything is written:
// renaming onto it would replace the device node itself.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace attenuvis::io {

// One output file, written under a temporary name and renamed into place by commit().
class StagedFile {
 public:
  // Throws std::runtime_error naming `path` when it cannot be staged.
  explicit StagedFile(std::string path);
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  ~StagedFile();  // removes the temporary unless committed

  const std::string& path() const { return path_; }
  const std::string& temporary_path() const { return temporary_; }

  // Replaces the temporary's contents with `text`.
  void write(std::string_view text);
  // Renames the temporary onto path(); throws if that fails (the temporary is removed).
  void commit();

 private:
  std::string path_, temporary_;
  bool committed_ = false;
};

// Throws std::runtime_error when `path` exists and is not a regular file.
void require_regular_or_absent(const std::string& path);

// Writes `text` to `path` through a StagedFile.
void write_file_atomically(const std::string& path, std::string_view text);
// Same, with the text produced by `fill` (a stream error is reported as a failure).
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill);

// Several outputs of one run: each is staged, and commit_all() renames them
// only after every one was written, so a failure leaves none of them behind.
class StagedFiles {
 public:
  // Stages `path`; throws if it equals a path staged before (two outputs on one file).
  StagedFile& add(const std::string& path);
  void commit_all();

 private:
  std::vector<StagedFile> files_;
};

}  // namespace attenuvis::io
