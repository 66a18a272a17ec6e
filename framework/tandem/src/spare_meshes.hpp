#pragma once
// Meshes of surfaces destroyed on a thread, kept for the next surfaces made there
// (keep_surface_storage() in simplify.hpp turns it on for the thread; off by default).

#include <cstddef>
#include <memory>

#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

// An empty mesh: a kept one (with its room) when the thread has one, else a new one.
std::unique_ptr<HalfedgeMesh> take_spare_mesh();
// Keeps `mesh`, emptied, for the thread's next surface when keeping is on (else frees it). `leaf`:
// it held a one-block surface (its room sets how much room any kept mesh may have). Never throws:
// a mesh that cannot be kept is freed.
void keep_spare_mesh(std::unique_ptr<HalfedgeMesh> mesh, bool leaf) noexcept;
// The bytes of mesh storage kept on this thread (for tests).
std::size_t spare_surface_storage_bytes();

} // namespace geotandem::tandem::detail
