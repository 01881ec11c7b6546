// Replaces TetGen's error exit, terminatetetgen(), whose Debian build crashes the process.
//
// TetGen 1.5.0 reports every error (self-intersecting facets, tiny features, internal errors) by
// calling terminatetetgen(mesh, code). libtet1.5 is built with TETLIBRARY, where that function
// frees the mesh's memory pools and throws the int code; the tetgenmesh that owns the pools is a
// local of tetrahedralize(), so its destructor frees them again while the exception unwinds: a
// double free that segfaults (in memorypool::~memorypool) before any catch can run.
//
// libtet calls terminatetetgen through its PLT, so this definition, exported by the executable
// (the linker exports it because libtet refers to it), is the one that runs: it only throws, and
// the destructor frees the pools once. Tetrahedralize.cpp checks at run time that this definition
// is the one the dynamic linker resolves, and refuses to run TetGen otherwise.
//
// This file must not include tetgen.h: its inline definition of the same function would clash.
class tetgenmesh;

void terminatetetgen(tetgenmesh* /*mesh*/, int code) { throw code; }

namespace orthosim::detail {

// Its address, for the run-time check; calling this also keeps this file linked from the library.
void* tetgenTerminateOverride() {
  void (*f)(tetgenmesh*, int) = &terminatetetgen;
  return reinterpret_cast<void*>(f);
}

}  // namespace orthosim::detail
