// header_libraries.cpp - the implementations of the header-only readers, which the host build links from Debian.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
