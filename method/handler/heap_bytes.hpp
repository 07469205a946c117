#pragma once
/// Bytes a container holds on the heap (its capacity, not its size: what it
/// occupies), for the handlers' memory accounting (CollisionHandler::
/// memory_bytes). The containers a handler keeps between steps only grow
/// (cleared and refilled, swapped, never moved out or shrunk), so at the end
/// of a run the figure is their peak. Buffers local to one call and
/// allocator overhead are not counted.

#include <cstddef>
#include <vector>

namespace tcb {

template <typename T>
std::size_t heap_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

template <typename T>
std::size_t heap_bytes(const std::vector<std::vector<T>>& v) {
  std::size_t bytes = v.capacity() * sizeof(std::vector<T>);
  for (const auto& inner : v) bytes += heap_bytes(inner);
  return bytes;
}

}  // namespace tcb
