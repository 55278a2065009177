// Refusing an input that would not fit in memory, with the size it would need, before it is
// allocated: without an address-space limit Linux overcommits and the kernel kills the process
// instead of letting an allocation fail (docs/robustness.md#memory).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace phonglab {

// The memory this process may still allocate: MemAvailable of /proc/meminfo, and under an
// address-space limit (RLIMIT_AS) half of what is left of it (reservations run about twice what
// is touched); nullopt when neither is known.
std::optional<std::size_t> available_memory();

// "" when `need` bytes fit in `available` (nullopt: unknown, so allowed), else the refusal:
// "<what> would need about 12.3 GiB (<detail>) but about 8.1 GiB are available".
std::string memory_refusal(std::size_t need, std::optional<std::size_t> available, const std::string& what,
                           const std::string& detail);

// memory_refusal against available_memory(), which is read only for inputs of 16 MiB or more
// (every small scene, mesh and lesson loads without opening /proc).
std::string refuse_if_too_large(std::size_t need, const std::string& what, const std::string& detail);

// Bytes shown as "512 KiB", "12.3 MiB", "8.1 GiB".
std::string byte_size(std::size_t bytes);

// What reading a mesh needs, from its prescan counts: the parser's copy, the indexed mesh,
// the triangles in their BVH leaves and the BVH nodes (measured: docs/robustness.md).
std::size_t mesh_bytes_needed(std::size_t vertices, std::size_t normals, std::size_t triangles);

// What reading a JSON text of `bytes` needs: the DOM and the position index (measured).
std::size_t json_bytes_needed(std::size_t bytes);

}  // namespace phonglab
