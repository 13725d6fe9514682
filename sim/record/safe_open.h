// Opening the files metrosync writes and reads back without going through what someone else
// planted in a shared output folder (issue 29): a symbolic link at the name is never followed, a
// FIFO or device never opened for writing nor waited on, and what was opened is checked (fstat)
// to be a regular file with one name. Temporary files are created with O_EXCL, so a name that
// already exists -- a planted link, another process's file -- is never reused.
#pragma once

#include <stdexcept>
#include <string>

namespace metrosync {

// A file in an output folder that is not what metrosync writes: a symbolic link, a FIFO, a
// device, a directory, or a regular file with a second hard link. The command exits 2 (nothing
// of it is written through).
struct UnsafeFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Creates `path` as a new regular file for writing (O_CREAT | O_EXCL | O_NOFOLLOW); returns the
// descriptor, or -1 with errno EEXIST when the name is taken (by anything, a link included).
// Throws std::runtime_error on any other failure.
int createNewFile(const std::string& path);

// Opens an existing-or-new file for writing (append, or truncated when `truncate`; for reading
// too when `readable`); a symbolic link, a non-regular file or a file with other hard links at
// `path` throws UnsafeFileError.
int openOutputFile(const std::string& path, bool truncate, bool append, bool readable = false);

// Opens `path` for reading if it is a regular file (never waits on a FIFO, never follows a link
// at its last component); -1 with errno ENOENT when there is no such file; UnsafeFileError for
// anything else at the name.
int openRegularForReading(const std::string& path);

// The whole of a regular file ("" when absent), read through openRegularForReading.
std::string readRegularFile(const std::string& path);

}  // namespace metrosync
