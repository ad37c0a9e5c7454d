#pragma once
/// \file
/// Atomic file writes: a file is written under a temporary name in its own folder and renamed
/// over its final name only when complete, so a reader (or a resumed run after a kill) sees
/// either the old file, or nothing, or the whole new file, never a part of one. Errors are
/// FileError naming the final path.

#include <filesystem>
#include <functional>
#include <string>

namespace sewer3d {

/// Calls `write(temporary)` with a fresh path in `path`'s folder (created when missing) that
/// keeps `path`'s extension (writers choose the format from it: `.png`, `.tiff`), then renames
/// the temporary over `path`. If `write` throws, the temporary is removed and the exception
/// passes on; `path` is left as it was. A temporary left by a killed process is named
/// `.<file name>.tmp-<pid>-<n><extension>` and is never read.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write);

/// While one exists, the files WriteFileAtomically creates (those that did not exist before)
/// are noted, and removed again when it goes without Keep(): a command whose outputs belong
/// together (a module's JSON and pattern, a reconstruction's depth map and cloud) leaves none
/// of them when it fails part-way (a full disk). Files it replaced stay replaced. One at a time
/// per process; thread-safe.
class NewOutputs {
 public:
  NewOutputs();
  ~NewOutputs();
  NewOutputs(const NewOutputs&) = delete;
  NewOutputs& operator=(const NewOutputs&) = delete;
  /// The command finished: its files stay.
  void Keep() { keep_ = true; }

 private:
  bool keep_ = false;
};

/// create_directories for an output folder, FileError naming it when that fails; the folders
/// it creates are new outputs (NewOutputs).
void CreateOutputFolder(const std::filesystem::path& folder);

/// A fresh name beside `path` for a temporary file or folder: `.<file name>.tmp-<pid>-<n>` +
/// `path`'s extension; unique within and across processes. Nothing is created.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& path);

/// WriteTextFile (text_file.hpp) through WriteFileAtomically.
void WriteTextFileAtomically(const std::filesystem::path& path, const std::string& text);

/// Before work whose result goes to `path`: FileError when `path` is a folder, a FIFO, socket or
/// device, or when the nearest existing folder above it is no folder (a file) or not writable.
/// Creates nothing. Commands writing several files check them all first, so that a refusal
/// leaves none written.
void CheckOutputFile(const std::filesystem::path& path);

/// True when `path` names an existing regular file (no exception).
bool IsRegularFile(const std::filesystem::path& path);

/// Removes `folder` and everything below it; nothing happens when it does not exist. FileError
/// when something cannot be removed.
void RemoveFolder(const std::filesystem::path& folder);

/// Removes the temporaries (`.<name>.tmp-…`, files or folders) that killed writers left
/// anywhere below `folder`; returns how many. Call only while no other process writes there
/// (hold its FolderLock).
int RemoveStaleTemporaries(const std::filesystem::path& folder);

/// An exclusive lock on a folder (an advisory lock on `folder/.lock`, released when the object
/// goes or the process dies, so a killed run never leaves a stale lock). FileError when another
/// process holds it or it cannot be taken.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) noexcept;

 private:
  int fd_ = -1;
};

}  // namespace sewer3d
