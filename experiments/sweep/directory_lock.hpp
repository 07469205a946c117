#pragma once
/// An exclusive lock on a result directory, held while a sweep writes the
/// files every shard rewrites (summary.csv, configurations.csv, sweep.json).
/// Shards of one sweep (a Slurm array, GNU parallel) share DIR and finish in
/// any order; without the lock two of them write the same temporary file at
/// once, and a shard that scanned DIR earlier could rename its older summary
/// over a later, complete one. With it, the shard that writes last scanned
/// last, so it saw every run any finished shard completed.
///
/// A POSIX record lock (fcntl F_SETLKW) on DIR/.summary.lock: it works on
/// NFS (through lockd), unlike flock on older kernels, and the kernel drops it
/// when the holder dies, so a cancelled shard never leaves DIR locked. The
/// lock file itself stays (empty); it is not a result.

#include <filesystem>

namespace tcb {

class DirectoryLock {
 public:
  /// Blocks until the lock on `dir`/.summary.lock is ours.
  /// std::runtime_error when the lock file cannot be opened or locked.
  explicit DirectoryLock(const std::filesystem::path& dir);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int m_fd = -1;
};

}  // namespace tcb
