#pragma once
// Debian's tinygltf header (libtinygltf-dev), compiled into reenact under a private namespace.
//
// Why not link Debian's libtinygltf.so: Debian's libdraco (which proto/ links) bundles an
// older tinygltf and exports its symbols (tinygltf::TinyGLTF::LoadASCIIFromFile, ...) with
// other class layouts; with both libraries in one process, calls resolve into either, which
// broke loading (.gltf reads failed with "FS callback not set") and risks memory corruption.
// Renaming the namespace makes our copy's symbols distinct from draco's.
//
// tinygltf_impl.cc holds the implementation (with a file-local stb_image); include this
// header, never <tiny_gltf.h> directly, and use the names as tinygltf::... .

#define tinygltf reenact_tinygltf
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#include <tiny_gltf.h>
