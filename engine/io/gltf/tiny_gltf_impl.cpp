// tinygltf's implementation (its header is the library; Debian's README.Debian asks for this one
// unit). Images are never decoded or read: mostyle wants nodes and animations only, and a file
// whose image data is broken still has a good animation. gltf_read.cpp includes the header with
// the same settings.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
