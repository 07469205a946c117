#pragma once
/// The process's peak resident memory, for the memory-per-tet figure of a run.
///
/// Read from VmHWM in /proc/self/status (Linux): the high-water mark of this
/// process's own address space. getrusage's ru_maxrss is not used because it
/// survives execve: a run a sweep forks and executes would report the sweep
/// process's peak if that were larger.
///
/// Contract: bytes (the kernel reports KiB; multiplied by 1024), or nullopt
/// where /proc is not available or has no VmHWM line. The peak covers
/// everything the process held: meshes, solver, oracle (CGAL, FCL), result
/// buffers, not only collision handling.

#include <cstdint>
#include <filesystem>
#include <optional>

namespace tcb {

std::optional<std::uint64_t> peak_resident_bytes();

/// The VmHWM line of a status file in /proc/<pid>/status format (exposed for
/// tests). nullopt when the file cannot be read or has no well-formed line.
std::optional<std::uint64_t> peak_resident_bytes(const std::filesystem::path& status_file);

}  // namespace tcb
