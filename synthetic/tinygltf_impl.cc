// The implementation of tinygltf_private.h: tinygltf's code, with stb_image compiled
// file-local (static) so that no stbi_* symbol can clash with another library's copy.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#define TINYGLTF_IMPLEMENTATION
#include "synthetic/tinygltf_private.h"
