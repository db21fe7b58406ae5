// The project's own PLY reader (issue 16). Debian's Assimp 5.2 reader looped forever, wrote
// past its arrays and allocated whatever a count claimed on malformed files, one new way
// every few minutes of fuzzing; this reader checks each count against the bytes left and
// names the place of each fault.
#pragma once

#include <cstddef>
#include <filesystem>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

// A PLY file's surface (Turk's format: an ASCII header, then ASCII or binary data of either
// byte order): the `vertex` element's x, y, z and, when all three are there, nx, ny, nz; the
// triangles of the `face` element's vertex_indices (or vertex_index) lists, polygons as fans,
// and of `tristrips` (−1 restarts a strip). Other elements and properties are read past; faces
// of fewer than three vertices are dropped; no normals without all of nx, ny, nz. `file`
// names the errors.
Mesh readPly(const std::filesystem::path& file, const char* data, std::size_t size);

}  // namespace cutaway
